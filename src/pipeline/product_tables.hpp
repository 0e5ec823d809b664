// The registry is assembled from one table per family of products, each in
// its own file (atmosphere_products.cpp, noise_products.cpp, ...), so adding a
// product touches one table and one schema file.
#pragma once

#include <vector>

#include "pipeline/product.hpp"

namespace skybake {

void add_atmosphere_products(std::vector<ProductInfo>& registry);
void add_noise_products(std::vector<ProductInfo>& registry);
void add_cloud_products(std::vector<ProductInfo>& registry);
void add_bruneton_products(std::vector<ProductInfo>& registry);
void add_sky_light_products(std::vector<ProductInfo>& registry);

// What every product states (product.hpp): its name and one-line summary,
// its size axes with their default and largest sizes, its baker and its
// cost per texel. The family helpers below add their family's defaults
// (formats, scene sections, ...) on top (product_registry.cpp).
ProductInfo basic_product(std::string name, std::string summary, std::vector<std::string> axes,
                          std::vector<int> size, std::vector<int> max_size, BakeFn bake,
                          double ns_per_texel);

// An atmosphere LUT product reading the planet and atmosphere sections, EXR
// and DDS by default (atmosphere_products.cpp).
ProductInfo atmosphere_lut_product(std::string name, std::string summary,
                                   std::vector<std::string> axes, std::vector<int> size,
                                   std::vector<int> max_size, std::vector<std::string> dependencies,
                                   BakeFn bake, double ns_per_texel);

// The problems of an output's converged Psi_ms field (its `scattering_shape`
// and the options of converged_multiscattering_spec): a 4D shape
// bake_bruneton accepts, within the iteration's memory (atmosphere_products.cpp).
std::vector<ProductProblem> converged_field_problems(const OutputSpec& spec);

}  // namespace skybake

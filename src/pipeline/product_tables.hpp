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

// Semantic rules of a scene's resolved "clouds" section (pointers relative to
// the section), checked at preset load.
std::vector<ProductProblem> clouds_section_problems(const nlohmann::json& clouds);

}  // namespace skybake

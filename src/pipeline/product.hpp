// The product registry: every asset skybake can bake, what it reads, its
// default and maximum size, and the function that bakes it. pipeline/ is the
// only layer that knows every product; bakers in atmosphere/, noise/ and
// clouds/ are pure functions that know nothing of presets or files.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Baked textures of the products a baker depends on, by product name.
using ProductInputs = std::map<std::string, const Texture*>;

using BakeFn = std::function<Texture(const Scene&, const OutputSpec&, const ProductInputs&,
                                     const BakeContext&)>;

struct ProductInfo {
  std::string name;                          // "transmittance"
  std::string summary;                       // one line for --help and plan
  std::vector<std::string> axes;             // size axes in preset order, e.g. {"mu", "r"}
  std::vector<int> default_size;             // one per axis
  std::vector<int> max_size;                 // one per axis; larger is refused at load
  std::vector<std::string> default_formats;  // when the preset gives none
  std::vector<std::string> allowed_formats;  // subset of exr, dds, vdb, png
  std::vector<std::string> dependencies;     // products whose textures bake() reads
  std::vector<std::string> scene_sections;   // top-level preset keys the result depends on
  std::string default_dds_format;            // empty: from precision and channel count
  BakeFn bake;
  // Rough cost for farm scheduling: single-thread nanoseconds per output
  // texel at default settings (measured with bench/, see the issue notes).
  double ns_per_texel = 1000.0;
};

// All products, in a stable order (dependencies before dependents).
const std::vector<ProductInfo>& product_registry();

// nullptr when unknown.
const ProductInfo* find_product(const std::string& name);

// Names of all products, for messages ("expected one of ...").
std::vector<std::string> product_names();

}  // namespace skybake

// The product table. Adding a product = a baker in its layer, an entry here,
// and schemas/products/<name>.schema.json for its options.
#include "pipeline/product.hpp"

#include "atmosphere/transmittance_lut.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

namespace {

const std::vector<std::string> kAtmosphereSections = {"planet", "atmosphere"};

Texture bake_transmittance(const Scene& scene, const OutputSpec& spec, const ProductInputs&,
                           const BakeContext& ctx) {
  TransmittanceLutSpec lut;
  lut.width = spec.size.at(0);
  lut.height = spec.size.at(1);
  lut.steps = option_int(spec, "steps", lut.steps);
  return bake_transmittance_lut(scene.atmosphere, lut, ctx);
}

std::vector<ProductInfo> make_registry() {
  std::vector<ProductInfo> r;
  r.push_back({"transmittance",
               "transmittance to the top of the atmosphere, (mu, r) Bruneton/Hillaire 2020 5.2",
               {"mu", "r"},
               {256, 64},
               {4096, 4096},
               {"exr", "dds"},
               {"exr", "dds", "png"},
               {},
               kAtmosphereSections,
               "",
               bake_transmittance});
  return r;
}

}  // namespace

const std::vector<ProductInfo>& product_registry() {
  static const std::vector<ProductInfo> registry = make_registry();
  return registry;
}

const ProductInfo* find_product(const std::string& name) {
  for (const ProductInfo& p : product_registry())
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string> product_names() {
  std::vector<std::string> names;
  for (const ProductInfo& p : product_registry()) names.push_back(p.name);
  return names;
}

}  // namespace skybake

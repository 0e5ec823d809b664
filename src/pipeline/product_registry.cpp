// The product table, assembled from the family tables (product_tables.hpp).
// Adding a product = a baker in its layer, an entry in its family's table,
// and schemas/products/<name>.schema.json for its options.
#include "pipeline/product.hpp"

#include <utility>

#include "pipeline/product_tables.hpp"

namespace skybake {

namespace {

std::vector<ProductInfo> make_registry() {
  std::vector<ProductInfo> r;
  add_atmosphere_products(r);
  add_bruneton_products(r);
  add_sky_light_products(r);
  add_noise_products(r);
  add_cloud_products(r);
  return r;
}

}  // namespace

ProductInfo basic_product(std::string name, std::string summary, std::vector<std::string> axes,
                          std::vector<int> size, std::vector<int> max_size, BakeFn bake,
                          double ns_per_texel) {
  ProductInfo p;
  p.name = std::move(name);
  p.summary = std::move(summary);
  p.axes = std::move(axes);
  p.default_size = std::move(size);
  p.max_size = std::move(max_size);
  p.bake = std::move(bake);
  p.ns_per_texel = ns_per_texel;
  return p;
}

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

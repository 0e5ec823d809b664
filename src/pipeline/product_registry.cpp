#include "pipeline/product.hpp"

namespace skybake {

const std::vector<ProductInfo>& product_registry() {
  static const std::vector<ProductInfo> registry = {};
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

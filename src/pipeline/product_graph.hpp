// The product graph of one scene (after ninja's Node/Edge): the requested
// products plus everything they depend on, in dependency order, each with the
// hashes that decide whether its files are current. Nothing outside this
// closure is ever computed (docs/architecture.md, "Data flow").
#pragma once

#include <string>
#include <vector>

#include "pipeline/product.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

struct GraphNode {
  const ProductInfo* info = nullptr;
  OutputSpec spec;           // as requested, or the product's defaults for a dependency
  bool requested = false;    // true: written to disk; false: computed in memory only
  std::vector<size_t> deps;  // indices of the nodes this one reads
  // Hash of everything that determines the texture values: tool version,
  // product, the scene sections it reads, its size and product options, and
  // the value hashes of its dependencies. Dependents hash this one.
  std::string value_hash;
  // value_hash plus what shapes the files (name, formats, precision, DDS format).
  std::string input_hash;
};

struct ProductGraph {
  std::vector<GraphNode> nodes;  // dependencies before dependents
  const GraphNode* find(const std::string& product) const;
};

// Builds the graph for `scene`. `only` (may be empty = everything the scene
// asks for) restricts the requested products; each name must be a product the
// scene requests, else UsageError (with "did you mean" for near misses).
ProductGraph build_product_graph(const Scene& scene, const std::vector<std::string>& only);

// The spec a product gets when only a dependency: registry defaults.
OutputSpec default_spec(const ProductInfo& info);

}  // namespace skybake

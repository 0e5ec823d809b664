// Whether an output on disk is current (after ninja's dirty check): one short
// function, a readable reason for each case, shown by `plan` and `bake -v`.
#pragma once

#include <filesystem>
#include <string>

#include "io/manifest.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

struct Freshness {
  bool current = false;
  std::string reason;  // "up to date", "not baked yet", "inputs changed", "missing file x"...
};

Freshness check_freshness(const GraphNode& node, const Manifest& manifest,
                          const std::filesystem::path& scene_dir);

}  // namespace skybake

// Whether an output on disk is current (after ninja's dirty check): one short
// function, a readable reason for each case, shown by `plan` and `bake -v`.
//
// An output is current when the manifest lists it with the node's input hash
// and every file it records is on disk with the recorded size and content.
// The size is always compared; the content hash only when the file's
// modification time differs from the one in the bake log (a copied, touched
// or rewritten file), or for every file under `verify`.
#pragma once

#include <filesystem>
#include <string>

#include "io/bake_log.hpp"
#include "io/manifest.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

struct Freshness {
  bool current = false;
  std::string reason;  // "up to date", "not baked yet", "inputs changed", "missing file x"...
};

struct FreshnessOptions {
  const BakeLog* log = nullptr;  // modification times at the last write; none: hash every file
  bool verify = false;           // hash every file whatever its time
};

Freshness check_freshness(const GraphNode& node, const Manifest& manifest,
                          const std::filesystem::path& scene_dir,
                          const FreshnessOptions& options = {});

}  // namespace skybake

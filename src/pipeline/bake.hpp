// Bakes one scene: builds its product graph, decides what is stale, computes
// the stale requested products and the dependencies they read (in memory),
// writes each requested output atomically, and merges the manifest.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/manifest.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

struct BakeOptions {
  std::filesystem::path out_dir = "out";
  std::vector<std::string> only;  // empty: everything the scene requests
  bool force = false;             // bake even what is current
  // Progress of one product: (product, fraction in [0, 1]); thread-safe.
  std::function<void(const std::string&, double)> on_progress;
  // Called when an output is finished (baked or found current).
  std::function<void(const struct OutputRecord&)> on_output;
};

struct OutputRecord {
  std::string product;
  std::string status;  // "baked" or "up to date"
  std::string reason;  // why it was (not) baked
  ManifestEntry entry;
};

struct BakeSummary {
  std::string scene;
  std::filesystem::path scene_dir;
  std::vector<OutputRecord> outputs;
  std::vector<std::string> computed;  // products computed in memory, in order
  std::vector<std::string> loaded;    // current dependencies read back from disk
  double seconds = 0.0;
};

BakeSummary bake_scene(const Scene& scene, const BakeOptions& options);

// <scene_dir>/.stamps/<output name>.stamp holds the output's input hash. It is
// rewritten only when the hash changes, so a build tool that compares file
// times (ninja with restat) sees an unchanged stamp when a re-run was a no-op.
std::filesystem::path stamp_path(const std::filesystem::path& scene_dir, const std::string& name);
void update_stamp(const std::filesystem::path& scene_dir, const std::string& name,
                  const std::string& hash);

}  // namespace skybake

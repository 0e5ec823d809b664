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
  bool verify = false;            // hash every recorded file (pipeline/freshness.hpp)
  // Progress of one product: (product, fraction in [0, 1]); thread-safe.
  std::function<void(const std::string&, double)> on_progress;
  // Called when an output is finished (baked or found current).
  std::function<void(const struct OutputRecord&)> on_output;
  // Called once an output is known current on disk and listed in the
  // manifest: (scene folder, output name, input hash). The CLI writes the
  // farm's stamps here (farm/stamps.hpp).
  std::function<void(const std::filesystem::path&, const std::string&, const std::string&)>
      on_recorded;
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
  // Worth telling but not failing the bake (pipeline/warnings.hpp), one per
  // warning of an output baked or found current: "<output>: <code>: <message>".
  // The CLI prints them and counts them on its summary line.
  std::vector<std::string> warnings;
  double seconds = 0.0;
};

BakeSummary bake_scene(const Scene& scene, const BakeOptions& options);

}  // namespace skybake

// The engine-neutral task graph of a whole catalog (docs/farm.md): one node per
// requested product of each scene, edges for dependencies between requested
// products of the same scene. A dependency a scene does not request is not a
// node: the dependent's task computes it in memory. Any engine (ninja,
// Slurm, ...) runs a node as `skybake bake PRESET --only PRODUCT`, or a whole
// scene's nodes as `skybake bake PRESET` (farm/emit.hpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/scene.hpp"

namespace skybake {

struct FarmNode {
  std::string id;                // "<scene>/<output name>"
  std::string preset;            // the scene preset file
  std::vector<std::string> sources;  // preset + referenced preset files
  std::string scene;
  std::string product;
  std::string input_hash;
  std::vector<std::string> files;  // output files, relative to the output folder
  std::string stamp;               // stamp file, relative to the output folder
  double estimated_seconds = 0.0;  // single-thread estimate, incl. in-memory dependencies
  std::vector<std::string> deps;   // ids of nodes this one reads
  bool current = false;            // up to date on disk
  std::string reason;
};

struct FarmGraph {
  std::filesystem::path out_dir;
  // A scene's nodes are consecutive, dependencies before dependents.
  std::vector<FarmNode> nodes;
};

FarmGraph build_farm_graph(const std::vector<Scene>& scenes, const std::filesystem::path& out_dir);

// {"nodes": [...], "edges": [[from, to], ...]} with up-to-date nodes left out
// (edges to them dropped: their files are read from disk).
nlohmann::json farm_graph_json(const FarmGraph& graph);

}  // namespace skybake

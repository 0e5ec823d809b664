// The engine-neutral task graph of a whole catalog (docs/farm.md): one node per
// requested product of each scene, edges for dependencies between requested
// products of the same scene. A dependency a scene does not request is not a
// node: the dependent's task computes it in memory. Any engine (ninja,
// Slurm, ...) runs a node as `skybake bake PRESET --only PRODUCT`.
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
  std::vector<FarmNode> nodes;  // dependencies before dependents within a scene
};

FarmGraph build_farm_graph(const std::vector<Scene>& scenes, const std::filesystem::path& out_dir);

// {"nodes": [...], "edges": [[from, to], ...]} with up-to-date nodes left out
// (edges to them dropped: their files are read from disk).
nlohmann::json farm_graph_json(const FarmGraph& graph);

struct EmitOptions {
  std::string skybake;   // the executable to run (absolute path)
  std::string launcher;  // prefix, e.g. "srun -n1 -c1 --exact --quiet"; empty = run directly
  int threads = 1;       // --threads for each task
  int chunk = 1;         // slurm: presets per array task
  int max_parallel = 0;  // slurm: %N array throttle; 0 = none
  bool strict = false;   // each task runs `bake --strict`: a warning fails it
};

// A ninja file: one edge per node, `restat = 1` and stamp files so a task
// that finds its product current changes nothing and stops nothing.
std::string emit_ninja(const FarmGraph& graph, const EmitOptions& options);

// An sbatch script with a job array: task i bakes presets [i*chunk, (i+1)*chunk),
// each preset's small graph inside the task.
std::string emit_slurm(const FarmGraph& graph, const EmitOptions& options);

}  // namespace skybake

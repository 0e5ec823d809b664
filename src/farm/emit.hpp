// Build files for existing engines from the farm graph (docs/farm.md): a ninja
// file (one edge per scene or per product) or an sbatch job-array script.
#pragma once

#include <string>

#include "farm/farm_graph.hpp"

namespace skybake {

// What one ninja edge runs (docs/decisions/product-graph.md).
enum class NinjaEdges {
  kScene,    // `skybake bake PRESET...`: every product of --chunk scenes, one process
  kProduct,  // `skybake bake PRESET --only PRODUCT`: one process per product
};

struct EmitOptions {
  std::string skybake;   // the executable to run (absolute path)
  std::string launcher;  // prefix, e.g. "srun -n1 -c1 --exact --quiet"; empty = run directly
  int threads = 1;       // --threads for each task
  int chunk = 1;         // presets per slurm array task, or per ninja edge of kScene
  int max_parallel = 0;  // slurm: %N array throttle; ninja: a pool of that depth; 0 = none
  bool strict = false;   // each task runs `bake --strict`: a warning fails it
  NinjaEdges edges = NinjaEdges::kScene;
};

// A ninja file: `restat = 1` and stamp files, so a task that finds its
// products current changes nothing and stops nothing. Scene edges have every
// stamp of their scenes as outputs; product edges one stamp, and the stamps of
// the products they read as inputs.
std::string emit_ninja(const FarmGraph& graph, const EmitOptions& options);

// An sbatch script with a job array: task i bakes presets [i*chunk, (i+1)*chunk),
// each preset's small graph inside the task.
std::string emit_slurm(const FarmGraph& graph, const EmitOptions& options);

}  // namespace skybake

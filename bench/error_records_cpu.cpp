// CPU time of each atmosphere table's bake and of its error record
// (docs/decisions/error-records.md), one thread,
// in one process: each preset's graph is baked in memory (no files), every
// BakeFn and MeasureFn timed with the thread's CPU clock, REPEAT times, and
// the medians printed. Steadier than bench/error_cost.sh's wall times on a
// loaded machine; the same products and the same records. A 4D family
// (bruneton_families.hpp) is forgotten before each repeat, so its bake is
// timed every time, under the first of its products the graph bakes (the
// others read it from the cache: compare the scene's totals).
//
//   build/bench/error_records_cpu [--repeat N] [--scalar] PRESET...
//        --scalar: every kernel on Highway's scalar target
//        (docs/architecture.md "Kernels")
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <hwy/targets.h>
#include <tbb/global_control.h>

#include "pipeline/bruneton_families.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"

using namespace skybake;

namespace {

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Times {
  std::vector<double> bake, error;
};

// One in-memory bake of the scene's graph; adds each requested measured
// output's times to `times`.
void bake_once(const Scene& scene, std::map<std::string, Times>& times) {
  forget_families();  // else every repeat but the first times a cached 4D family
  const ProductGraph graph = build_product_graph(scene, {});
  std::vector<std::optional<Texture>> textures(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const GraphNode& node = graph.nodes[i];
    ProductInputs inputs;
    for (size_t d : node.deps) inputs[graph.nodes[d].info->name] = &*textures[d];
    const double t0 = cpu_seconds();
    textures[i] = node.info->bake(scene, node.spec, inputs, BakeContext{});
    const double t1 = cpu_seconds();
    if (!node.requested || !node.info->measure_error) continue;
    node.info->measure_error(scene, node.spec, inputs, *textures[i]);
    const double t2 = cpu_seconds();
    times[node.spec.name].bake.push_back(t1 - t0);
    times[node.spec.name].error.push_back(t2 - t1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<std::string> presets;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::stoi(argv[++i]));
    else if (a == "--scalar")
      hwy::SetSupportedTargetsForTest(HWY_SCALAR);
    else
      presets.push_back(a);
  }
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  std::printf("| scene | output | bake ms | error ms | error / bake |\n|---|---|---|---|---|\n");
  for (const std::string& preset : presets) {
    const Scene scene = load_scene(preset);
    std::map<std::string, Times> times;
    for (int r = 0; r < repeat; ++r) bake_once(scene, times);
    double bake = 0.0, error = 0.0;
    for (const auto& [name, t] : times) {
      const double b = median(t.bake), e = median(t.error);
      bake += b;
      error += e;
      std::printf("| %s | %s | %.2f | %.2f | %.1f%% |\n", scene.name.c_str(), name.c_str(), 1e3 * b,
                  1e3 * e, 100.0 * e / std::max(b, 1e-12));
    }
    std::printf("| %s | measured outputs | %.2f | %.2f | **%.1f%%** |\n", scene.name.c_str(),
                1e3 * bake, 1e3 * error, 100.0 * error / std::max(bake, 1e-12));
  }
  return 0;
}

// Research tool, not a benchmark: how far the aerial-perspective record's
// reference (pipeline/atmosphere_errors.cpp) is from a much denser march at
// the record's own query points, per preset (docs/decisions/error-records.md). Each preset's
// graph is baked in memory; for its aerial_perspective table it prints, max /
// rms relative over the queries and channels (core/error_stats.hpp):
//   record    the table against the record's reference (the manifest's figure)
//   midpoint  the midpoint march (sources read at each segment's midpoint) at
//             N steps over the depth range, against the dense march
//   ends      the march with the sources at the segments' ends
//             (IntegrationOptions::sources_at_ends) at N, against the same
//   dense     the ends march at DENSE against the midpoint march at DENSE,
//             the dense march's own convergence
// and the segments over the queries, and (--time R) the median CPU ms of R
// runs of each rule's 256 marches on one thread. The dense march is the
// midpoint march at DENSE steps over the range (default 32 x 100).
//
//   build/bench/aerial_reference_convergence [--steps N,N...] [--dense N] [--time R]
//        [--rule midpoint|ends] PRESET...
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "core/error_stats.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"
#include "verify/error_references.hpp"
#include "verify/query_points.hpp"

using namespace skybake;

namespace {

struct Marches {
  std::vector<glm::dvec3> values;
  size_t segments = 0;
  double cpu_ms = 0.0;  // median over the runs
};

int g_runs = 1;
std::string g_rule;  // --rule: only this rule's candidates (midpoint or ends)

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Every query's luminance marched with `steps` over the depth range.
Marches march_all(const Atmosphere& atm, const AerialPerspectiveSpec& baked,
                  const Texture& transmittance, const Texture* multiscattering,
                  const MultiscatteringMapping& mapping, int steps, bool at_ends) {
  IntegrationOptions options;
  options.block_exponentials = true;
  options.sources_at_ends = at_ends;
  options.multiscattering_mapping = &mapping;
  const glm::dvec3 sun = sun_direction(baked.sun_zenith_rad, baked.sun_azimuth_rad);
  Marches m;
  m.values.resize(size_t(kAerialQueries));
  std::vector<double> times;
  for (int run = 0; run < g_runs; ++run) {
    const double t0 = cpu_seconds();
    tbb::parallel_for(size_t(0), m.values.size(), [&](size_t i) {
      const AerialQueryPoint q = aerial_query(atm, baked, i);
      m.values[i] =
          integrate_scattered_luminance(
              atm, transmittance, multiscattering, q.position, q.view_dir, sun, q.distance_m,
              aerial_reference_segments(q.distance_m, baked.depth_range_m, steps), options)
              .luminance;
    });
    times.push_back(cpu_seconds() - t0);
  }
  std::sort(times.begin(), times.end());
  m.cpu_ms = 1e3 * times[times.size() / 2];
  for (size_t i = 0; i < m.values.size(); ++i)
    m.segments += size_t(aerial_reference_segments(aerial_query(atm, baked, i).distance_m,
                                                   baked.depth_range_m, steps));
  return m;
}

ErrorStats compare(const std::vector<glm::dvec3>& values, const std::vector<glm::dvec3>& refs) {
  ErrorTally tally;
  for (size_t i = 0; i < values.size(); ++i)
    for (int c = 0; c < 3; ++c) tally.add(values[i][c], refs[i][c]);
  return tally.stats();
}

void print(const char* scene, const std::string& what, const ErrorStats& s, const Marches& m) {
  std::printf("| %s | %s | %.3e / %.3e | %zu | %.2f |\n", scene, what.c_str(), s.max_rel, s.rms_rel,
              m.segments, m.cpu_ms);
}

void run(const std::string& preset, const std::vector<int>& steps, int dense_steps) {
  const Scene scene = load_scene(preset);
  const ProductGraph graph = build_product_graph(scene, {});
  std::vector<Texture> textures(graph.nodes.size());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const GraphNode& node = graph.nodes[i];
    ProductInputs in;
    for (size_t d : node.deps) in[graph.nodes[d].info->name] = &textures[d];
    textures[i] = node.info->bake(scene, node.spec, in, BakeContext{});
    if (node.info->name != "aerial_perspective") continue;
    const Atmosphere& atm = scene.atmosphere;
    const AerialPerspectiveSpec baked = aerial_perspective_spec(node.spec);
    const Texture& t = *in.at("transmittance");
    const Texture* ms = in.count("multiscattering") ? in.at("multiscattering") : nullptr;
    const MultiscatteringMapping mapping =
        ms ? multiscattering_mapping_of(*ms) : MultiscatteringMapping{};
    const Marches dense = march_all(atm, baked, t, ms, mapping, dense_steps, false);
    const Marches dense_ends = march_all(atm, baked, t, ms, mapping, dense_steps, true);
    const char* name = scene.name.c_str();
    std::vector<glm::dvec3> table(dense.values.size());
    for (size_t q = 0; q < table.size(); ++q) {
      const AerialQueryPoint p = aerial_query(atm, baked, q);
      table[q] = glm::dvec3(
          lookup_aerial_perspective(textures[i], baked.depth_range_m, p.screen_uv, p.distance_m));
    }
    print(name, "table against dense", compare(table, dense.values), dense);
    print(name, "dense: ends against midpoint", compare(dense_ends.values, dense.values),
          dense_ends);
    for (int n : steps) {
      for (const bool at_ends : {false, true}) {
        const std::string rule = at_ends ? "ends" : "midpoint";
        if (!g_rule.empty() && rule != g_rule) continue;
        const Marches m = march_all(atm, baked, t, ms, mapping, n, at_ends);
        print(name, rule + " " + std::to_string(n), compare(m.values, dense.values), m);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> steps = {kAerialReferenceSteps};
  int dense = 32 * kAerialReferenceSteps;
  std::vector<std::string> presets;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--steps" && i + 1 < argc) {
      steps.clear();
      std::stringstream list(argv[++i]);
      for (std::string n; std::getline(list, n, ',');) steps.push_back(std::stoi(n));
    } else if (a == "--rule" && i + 1 < argc) {
      g_rule = argv[++i];
    } else if (a == "--time" && i + 1 < argc) {
      g_runs = std::max(1, std::stoi(argv[++i]));
    } else if (a == "--dense" && i + 1 < argc) {
      dense = std::stoi(argv[++i]);
    } else {
      presets.push_back(a);
    }
  }
  // One thread, so that --time's CPU is the marches' own.
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  std::printf(
      "| scene | march | max / rms relative | segments | CPU ms |\n|---|---|---|---|---|\n");
  for (const std::string& preset : presets) run(preset, steps, dense);
  return 0;
}

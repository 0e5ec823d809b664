// Benchmarks of the reference path tracer (reference/path_tracer.hpp) on one
// TBB thread, 256 paths per view, 6 vertices (the settings of
// tests/reference/extreme_bruneton_test.cpp):
//   BM_PathTracerAtmosphere1m  Earth's media in a shell 1 m thick
//                              (presets/extreme/atmosphere_1m.json), 54 views:
//                              the forced first collision is the cost there
//   BM_PathTracerEarth         Earth, the same views, for scale
// Items are views.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "support/test_atmospheres.hpp"
#include "core/math.hpp"
#include "reference/path_tracer.hpp"

namespace skybake {
namespace {

struct View {
  glm::dvec3 position_m, view_dir, sun_dir;
};

glm::dvec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kPi / 180.0, a = azimuth_deg * kPi / 180.0;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

// Cameras on the ground looking up and at the top looking down, three suns
// and three azimuths: the views of extreme_bruneton_test.cpp.
std::vector<View> views(const Atmosphere& atm) {
  std::vector<View> out;
  const glm::dvec3 ground(0.0, 0.0, atm.bottom_radius_m), top(0.0, 0.0, atm.top_radius_m);
  for (double sun : {90.0, 30.0, 0.0})
    for (double azimuth : {0.0, 90.0, 180.0}) {
      for (double elevation : {2.0, 20.0, 70.0})
        out.push_back({ground, direction(elevation, azimuth), direction(sun, 0.0)});
      for (double elevation : {-70.0, -20.0, -5.0})
        out.push_back({top, direction(elevation, azimuth), direction(sun, 0.0)});
    }
  return out;
}

void trace_views(benchmark::State& state, const Atmosphere& atm) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.samples = 256;
  spec.max_bounces = 6;
  const std::vector<View> all = views(atm);
  for (auto _ : state)
    for (const View& v : all)
      benchmark::DoNotOptimize(tracer.trace(v.position_m, v.view_dir, v.sun_dir, spec));
  state.SetItemsProcessed(state.iterations() * int64_t(all.size()));
}

void BM_PathTracerAtmosphere1m(benchmark::State& state) {
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.top_radius_m = atm.bottom_radius_m + 1.0;
  trace_views(state, atm);
}
BENCHMARK(BM_PathTracerAtmosphere1m)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void BM_PathTracerEarth(benchmark::State& state) {
  trace_views(state, fixtures::earth_atmosphere());
}
BENCHMARK(BM_PathTracerEarth)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace skybake

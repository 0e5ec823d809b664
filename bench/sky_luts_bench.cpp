// Bake times of the Hillaire 2020 sky LUTs for Earth: the
// multiple-scattering LUT (32 x 32, 64 directions x 20 steps), 8 sky-view
// layers (192 x 108, 30 steps), the aerial-perspective volume (32^3, 2 steps
// per slice) and the full set with the transmittance LUT (256 x 64) in
// front, each at 1 and 2 threads (tbb::global_control inside the benchmark).
// Target: the full set under 0.5 s wall on 2 cores.
// Run: skybake_bench --benchmark_filter=Sky
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "support/test_atmospheres.hpp"
#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

tbb::global_control threads(const benchmark::State& state) {
  return tbb::global_control(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
}

// Eight views: the sun from noon to just below the horizon at the ground,
// and two higher viewers.
SkyviewLutSpec eight_views() {
  SkyviewLutSpec spec;
  const double deg = kPi / 180.0;
  spec.views = {{0.0, 0.0},      {0.0, 30 * deg}, {0.0, 60 * deg}, {0.0, 80 * deg},
                {0.0, 88 * deg}, {0.0, 92 * deg}, {1e3, 45 * deg}, {10e3, 85 * deg}};
  return spec;
}

struct Inputs {
  Atmosphere atm = fixtures::earth_atmosphere();
  Texture transmittance = bake_transmittance_lut(atm, {}, {});
  Texture multiscattering = bake_multiscattering_lut(atm, transmittance, {}, {});
};

const Inputs& inputs() {
  static const Inputs in;
  return in;
}

void BM_SkyMultiscattering(benchmark::State& state) {
  const Inputs& in = inputs();
  auto limit = threads(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        bake_multiscattering_lut(in.atm, in.transmittance, {}, {}).data.data());
}

// The terminator mapping with the symmetric Gauss rule at 96 rays, the
// setting docs/reference.md "Direction rule" measures (compare with the
// default above: the paper's 64 Fibonacci directions).
void BM_SkyMultiscatteringTerminatorGauss96(benchmark::State& state) {
  const Inputs& in = inputs();
  MultiscatteringLutSpec spec;
  spec.directions = 96;
  spec.sun_mapping = SunMapping::terminator;
  spec.quadrature = DirectionQuadrature::symmetric_gauss;
  auto limit = threads(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        bake_multiscattering_lut(in.atm, in.transmittance, spec, {}).data.data());
}

void BM_SkySkyview8Layers(benchmark::State& state) {
  const Inputs& in = inputs();
  const SkyviewLutSpec spec = eight_views();
  auto limit = threads(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        bake_skyview_lut(in.atm, in.transmittance, in.multiscattering, spec, {}).data.data());
}

void BM_SkyAerialPerspective(benchmark::State& state) {
  const Inputs& in = inputs();
  auto limit = threads(state);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        bake_aerial_perspective_lut(in.atm, in.transmittance, in.multiscattering, {}, {})
            .data.data());
}

void BM_SkyFullSet(benchmark::State& state) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SkyviewLutSpec spec = eight_views();
  auto limit = threads(state);
  for (auto _ : state) {
    const Texture t = bake_transmittance_lut(atm, {}, {});
    const Texture ms = bake_multiscattering_lut(atm, t, {}, {});
    benchmark::DoNotOptimize(bake_skyview_lut(atm, t, ms, spec, {}).data.data());
    benchmark::DoNotOptimize(bake_aerial_perspective_lut(atm, t, ms, {}, {}).data.data());
  }
}

#define SKY_BENCH(fn) \
  BENCHMARK(fn)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
SKY_BENCH(BM_SkyMultiscattering);
SKY_BENCH(BM_SkyMultiscatteringTerminatorGauss96);
SKY_BENCH(BM_SkySkyview8Layers);
SKY_BENCH(BM_SkyAerialPerspective);
SKY_BENCH(BM_SkyFullSet);

}  // namespace
}  // namespace skybake

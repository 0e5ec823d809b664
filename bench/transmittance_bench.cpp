// Benchmarks of the transmittance LUT (atmosphere/transmittance_lut.hpp):
// the Earth bake at the default 256 x 64 x 40 steps with 1 and 2 TBB threads,
// and the cost of one ray (the unit of work of every texel).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "support/test_atmospheres.hpp"
#include "atmosphere/transmittance_lut.hpp"

namespace skybake {
namespace {

void BM_BakeTransmittanceEarth(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
  const Atmosphere atm = fixtures::earth_atmosphere();
  for (auto _ : state) {
    Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
    benchmark::DoNotOptimize(lut.data.data());
  }
  state.SetItemsProcessed(state.iterations() * 256 * 64);  // texels
}
BENCHMARK(BM_BakeTransmittanceEarth)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One horizontal ray from the ground (the longest in the table) with the
// ozone kinks to cut, at the default 40 steps.
void BM_ComputeTransmittanceToTopHorizon(benchmark::State& state) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        compute_transmittance_to_top(atm, atm.bottom_radius_m, 0.0, int(state.range(0))));
}
BENCHMARK(BM_ComputeTransmittanceToTopHorizon)->ArgName("steps")->Arg(40)->Arg(160);

}  // namespace
}  // namespace skybake

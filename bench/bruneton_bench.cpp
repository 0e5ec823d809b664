// Benchmarks of the precomputed-scattering bakes (docs/reference.md
// "Precomputed scattering"): Earth at the
// default sizes with 4 orders, on 1 and 2 TBB threads. The transmittance LUT
// (their input) is baked once outside the timed loop.
//   BM_BakeBrunetonEarth     4D scattering 32x128x32x8 + irradiance 64x16
//   BM_BakeScattering3dEarth azimuth-free 32x128x32 + gathering 32x32
//   BM_Bruneton*Stage        one stage at default sizes (where the time goes),
//                            on the best SIMD target of the CPU
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

const Texture& earth_transmittance() {
  static const Texture lut =
      bake_transmittance_lut(fixtures::earth_atmosphere(), TransmittanceLutSpec{}, BakeContext{});
  return lut;
}

void BM_BakeBrunetonEarth(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture& lut = earth_transmittance();
  for (auto _ : state) {
    BrunetonTextures t = bake_bruneton(atm, lut, BrunetonSpec{}, BakeContext{});
    benchmark::DoNotOptimize(t.scattering.data.data());
  }
  state.SetItemsProcessed(state.iterations() * 32 * 128 * 32 * 8);  // scattering texels
}
BENCHMARK(BM_BakeBrunetonEarth)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

void BM_BakeScattering3dEarth(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture& lut = earth_transmittance();
  for (auto _ : state) {
    Scattering3dTextures t = bake_scattering3d(atm, lut, Scattering3dSpec{}, BakeContext{});
    benchmark::DoNotOptimize(t.scattering.data.data());
  }
  state.SetItemsProcessed(state.iterations() * 32 * 128 * 32);
}
BENCHMARK(BM_BakeScattering3dEarth)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

// The stages of one 4D order, single-threaded: single scattering (once per
// bake), then per order the density and the multiple-scattering pass, on
// the 4D table's texels and in the sun's frame.
void BM_BrunetonStage(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture& lut = earth_transmittance();
  const ScatteringShape shape;
  const ScatteringPhases phases = scattering_phases(atm);
  const SingleScatteringTables single = bake_single_scattering(atm, lut, shape, 50, BakeContext{});
  const ScatteringOrder order1{&single.rayleigh, &single.mie, nullptr, &phases};
  const Texture density = bake_scattering_density(atm, lut, shape, order1, {}, 16, BakeContext{});
  const int kSunFrameAzimuths = sun_frame_azimuths(shape);
  SunFrameDensity sun_density, sun_per_sigma_s;
  bake_sun_frame_density(atm, lut, shape, order1, {}, 16, kSunFrameAzimuths, BakeContext{},
                         sun_per_sigma_s);
  divide_by_scattering(atm, sun_per_sigma_s);
  Texture delta;
  MultipleScatteringWork work;
  bake_multiple_scattering(atm, sun_per_sigma_s, 50, BakeContext{}, delta, work);  // its nodes
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0:
        benchmark::DoNotOptimize(bake_single_scattering(atm, lut, shape, 50, BakeContext{}));
        break;
      case 1:
        benchmark::DoNotOptimize(
            bake_scattering_density(atm, lut, shape, order1, {}, 16, BakeContext{}));
        break;
      case 2:
        benchmark::DoNotOptimize(
            bake_multiple_scattering(atm, shape, density, 50, BakeContext{}));
        break;
      case 3:
        bake_sun_frame_density(atm, lut, shape, order1, {}, 16, kSunFrameAzimuths, BakeContext{},
                               sun_density);
        break;
      default:
        bake_multiple_scattering(atm, sun_per_sigma_s, 50, BakeContext{}, delta, work);
        break;
    }
  }
}
BENCHMARK(BM_BrunetonStage)
    // stage 0 single, 1 density, 2 multiple, 3 density in the sun's frame,
    // 4 multiple over it (its rows' nodes made before), on the best SIMD target
    ->ArgNames({"stage"})
    ->DenseRange(0, 4)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

}  // namespace
}  // namespace skybake

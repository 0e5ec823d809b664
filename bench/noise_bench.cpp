// Bake times of the cloud noise set (docs/reference.md "Cloud noise"): the shape volume
// (128^3 RGBA), the detail volume (32^3 RGB), the curl texture (128^2 RGB) and
// the three together, each at 1 and 2 threads (tbb::global_control inside the
// benchmark), plus the cost of one pure Worley call for comparison with the
// ~2.4 us per call of TileableVolumeNoise. Target: the full set < 0.3 s wall
// on 2 cores. Run: skybake_bench --benchmark_filter=Noise
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "core/mip_chain.hpp"
#include "core/tiling_profiles.hpp"
#include "noise/curl_texture.hpp"
#include "noise/noise_volume.hpp"
#include "noise/worley.hpp"

namespace skybake {
namespace {

tbb::global_control threads(const benchmark::State& state) {
  return tbb::global_control(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
}

void BM_NoiseShape(benchmark::State& state) {
  auto limit = threads(state);
  for (auto _ : state) benchmark::DoNotOptimize(bake_noise_shape({}, {}).data.data());
}

void BM_NoiseDetail(benchmark::State& state) {
  auto limit = threads(state);
  for (auto _ : state) benchmark::DoNotOptimize(bake_noise_detail({}, {}).data.data());
}

void BM_NoiseCurl(benchmark::State& state) {
  auto limit = threads(state);
  for (auto _ : state) benchmark::DoNotOptimize(bake_curl({}, {}).data.data());
}

void BM_NoiseFullSet(benchmark::State& state) {
  auto limit = threads(state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(bake_noise_shape({}, {}).data.data());
    benchmark::DoNotOptimize(bake_noise_detail({}, {}).data.data());
    benchmark::DoNotOptimize(bake_curl({}, {}).data.data());
  }
}

void BM_NoiseWorleyCall(benchmark::State& state) {
  float x = 0.0f, sum = 0.0f;
  for (auto _ : state) {
    sum += worley3_f1({x, 0.37f * x, 0.61f * x}, glm::ivec3(16), 7u);
    x += 0.013f;
    if (x > 16.0f) x = 0.0f;
  }
  benchmark::DoNotOptimize(sum);
}

// The post-passes of the shape volume in a bake: the tiling record's
// profiles along one axis (0, 1, 2 for x, y, z) and the DDS mip chain.
const Texture& default_shape() {
  static const Texture t = bake_noise_shape({}, {});
  return t;
}

void BM_NoiseShapeTilingProfiles(benchmark::State& state) {
  const Texture& t = default_shape();
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  for (auto _ : state)
    benchmark::DoNotOptimize(compute_tiling_profiles(t, 0, int(state.range(0))).data());
}

void BM_NoiseShapeLowerMips(benchmark::State& state) {
  const Texture& t = default_shape();
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  for (auto _ : state) benchmark::DoNotOptimize(build_lower_mips(t, MipEdge::wrap).data());
}

}  // namespace

BENCHMARK(BM_NoiseShapeTilingProfiles)->DenseRange(0, 2)->ArgName("axis")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NoiseShapeLowerMips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NoiseShape)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_NoiseDetail)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_NoiseCurl)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_NoiseFullSet)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_NoiseWorleyCall)->Unit(benchmark::kNanosecond);

}  // namespace skybake

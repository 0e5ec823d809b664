// Bake times of the cloud noise set (docs/reference.md "Cloud noise"): the shape volume
// (128^3 RGBA), the detail volume (32^3 RGB), the curl texture (128^2 RGB) and
// the three together, each at 1 and 2 threads (tbb::global_control inside the
// benchmark), plus the cost of one pure Worley call for comparison with the
// ~2.4 us per call of TileableVolumeNoise. Target: the full set < 0.3 s wall
// on 2 cores. Run: skybake_bench --benchmark_filter=Noise
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

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

}  // namespace

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

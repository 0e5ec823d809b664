// What block compression costs on the shipped presets (docs/formats.md
// "Block compression"): every 8-bit output of the presets below is baked
// once, with its mip chain when the output has one, then encoded in the
// block format of its channel count (BC4 1, BC5 2, BC1 3, BC3 4) and, for
// comparison, in the 8-bit UNORM format the output writes by default. The
// timed loop is the encoding of every level and slice (2 threads); the
// counters are the DDS file's bytes and, per channel over every level, the
// RMS and largest error of the decoded file against the float texture.
// curl is measured as baked (RGB, BC1) and with "channels": "rg" (BC5).
//
// Run from the repository root (the presets are read from presets/):
//   build/bench/skybake_bench --benchmark_filter=BlockCompression
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product.hpp"

namespace skybake {
namespace {

struct Case {
  std::string preset, product;
  bool rg = false;  // curl with "channels": "rg"
};

// The output's texture as the bake makes it, with its mip chain.
std::vector<Texture> baked_chain(const Case& c) {
  const Scene scene = load_scene(c.preset);
  OutputSpec spec = *scene.find_output(c.product);
  if (c.rg) spec.options["channels"] = "rg";
  const ProductInfo& info = *find_product(c.product);
  const Texture tex = info.bake(scene, spec, {}, BakeContext{});
  if (spec.options.value("mips", info.default_mips)) return build_mip_chain(tex, MipEdge::wrap);
  return {tex};
}

BcFormat block_format_for(int channels) {
  static const BcFormat by_channels[] = {BcFormat::bc4, BcFormat::bc5, BcFormat::bc1,
                                         BcFormat::bc3};
  return by_channels[channels - 1];
}

// Decoded values of one slice: block format, or 8-bit UNORM (round(v * 255)).
std::vector<float> round_trip(const float* texels, int w, int h, int nc, bool block,
                              BcFormat format, size_t* bytes) {
  if (block) {
    const std::vector<uint8_t> blocks = encode_bc(texels, w, h, nc, format);
    *bytes += blocks.size();
    const std::vector<float> decoded = decode_bc(blocks.data(), w, h, format);
    const int dc = bc_decoded_channel_count(format);
    std::vector<float> out(size_t(w) * h * nc);
    for (size_t t = 0; t < size_t(w) * h; ++t)
      for (int c = 0; c < nc; ++c) out[t * nc + c] = decoded[t * dc + c];
    return out;
  }
  // R8, R8G8 or R8G8B8A8: 3 channels are stored in 4.
  *bytes += size_t(w) * h * size_t(nc == 3 ? 4 : nc);
  std::vector<float> out(texels, texels + size_t(w) * h * nc);
  for (float& v : out) v = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
  return out;
}

void BM_BlockCompression(benchmark::State& state, const Case& c, bool block) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  static std::map<std::string, std::vector<Texture>> cache;
  const std::string key = c.preset + c.product + (c.rg ? "rg" : "");
  if (!cache.count(key)) cache[key] = baked_chain(c);
  const std::vector<Texture>& chain = cache[key];
  const int nc = chain[0].channel_count();
  const BcFormat format = block_format_for(nc);
  size_t bytes = 0;
  std::vector<double> sse(nc), max_err(nc);
  size_t texels = 0;
  for (auto _ : state) {
    bytes = 0;
    std::fill(sse.begin(), sse.end(), 0.0);
    std::fill(max_err.begin(), max_err.end(), 0.0);
    texels = 0;
    for (const Texture& m : chain)
      for (int z = 0; z < m.depth; ++z) {
        const float* src = m.texel(0, 0, z);
        const std::vector<float> out = round_trip(src, m.width, m.height, nc, block, format, &bytes);
        for (size_t t = 0; t < size_t(m.width) * m.height; ++t, ++texels)
          for (int ch = 0; ch < nc; ++ch) {
            const double e = std::abs(double(out[t * nc + ch]) - src[t * nc + ch]);
            sse[ch] += e * e;
            max_err[ch] = std::max(max_err[ch], e);
          }
      }
  }
  state.SetLabel(block ? bc_format_name(format) : "unorm8");
  state.counters["bytes"] = double(bytes + 148);  // DX10 header
  const char* names = "RGBA";
  for (int ch = 0; ch < nc; ++ch) {
    state.counters[std::string("rms_") + names[ch]] = std::sqrt(sse[ch] / double(texels));
    state.counters[std::string("max_") + names[ch]] = max_err[ch];
  }
}

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"presets/clouds/horizon_zero_dawn.json", "noise_shape"},
      {"presets/clouds/horizon_zero_dawn.json", "noise_detail"},
      {"presets/clouds/horizon_zero_dawn.json", "curl"},
      {"presets/clouds/horizon_zero_dawn.json", "curl", true},
      {"presets/clouds/frostbite_packed.json", "noise_shape"},
      {"presets/clouds/frostbite_packed.json", "noise_detail"},
      {"presets/earth_storm.json", "weather"},
      {"presets/earth_storm.json", "cloud_types"},
      {"presets/earth_storm.json", "height_gradients"},
      {"presets/earth_storm.json", "cirrus"},
      {"presets/earth_fair_weather.json", "weather"},
      {"presets/earth_fair_weather.json", "cloud_types"},
      {"presets/earth_fair_weather.json", "cirrus"},
  };
  return all;
}

// Registered at start-up, one pair (block, unorm8) per case.
const bool registered = [] {
  for (const Case& c : cases()) {
    std::string name = c.preset.substr(c.preset.rfind('/') + 1);
    name = "BlockCompression/" + name.substr(0, name.size() - 5) + "/" + c.product +
           (c.rg ? "_rg" : "");
    for (const bool block : {true, false})
      benchmark::RegisterBenchmark((name + (block ? "/bc" : "/unorm8")).c_str(),
                                   [c, block](benchmark::State& s) { BM_BlockCompression(s, c, block); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
  }
  return true;
}();

}  // namespace
}  // namespace skybake

#include "noise/curl_texture.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "noise/curl.hpp"
#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"

namespace skybake {

std::vector<SpecProblem> spec_problems(const CurlSpec& spec) {
  std::vector<SpecProblem> out;
  auto range = [&](const char* field, long v, long lo, long hi) {
    if (v < lo || v > hi)
      out.push_back({field, fmt::format("expected {} .. {}, got {}", lo, hi, v)});
  };
  range("size", spec.size, 2, 4096);
  range("period", spec.period, 1, 4096);
  range("octaves", spec.octaves, 1, kMaxOctaves);
  if (out.empty() && (long(spec.period) << (spec.octaves - 1)) > spec.size / 2)
    out.push_back({"octaves", fmt::format("expected the finest octave period (period * "
                                          "2^(octaves - 1)) <= {} (size / 2), got {}",
                                          spec.size / 2, long(spec.period) << (spec.octaves - 1))});
  if (!(spec.gain > 0.0f && spec.gain <= 1.0f))
    out.push_back({"gain", fmt::format("expected a value in (0, 1], got {}", spec.gain)});
  if (!std::isfinite(spec.slice_z))
    out.push_back({"slice_z", fmt::format("expected a finite value, got {}", spec.slice_z)});
  return out;
}

Texture bake_curl(const CurlSpec& spec, const BakeContext& ctx) {
  const auto problems = spec_problems(spec);
  if (!problems.empty())
    throw Error(fmt::format("curl: {}: {}", problems[0].field, problems[0].message));
  const int n = spec.size;
  const glm::ivec2 period2(spec.period);
  const glm::ivec3 period3(spec.period);
  // The 3D potentials use their own seed so that B is not built from the
  // same random numbers as R and G.
  const uint32_t seed3 = stream_seed(spec.seed, 0x33643344);  // "3d3D"
  const int nc = spec.with_z ? 3 : 2;
  Texture tex(n, n, 1, 1, spec.with_z ? std::vector<std::string>{"R", "G", "B"}
                                      : std::vector<std::string>{"R", "G"});
  // Per-row maxima, reduced serially afterwards: a max is exact, so the scale
  // (and every texel) is independent of the thread count.
  std::vector<float> row_max_rg(n), row_max_b(n);
  ProgressCounter progress(ctx, size_t(n));
  tbb::parallel_for(0, n, [&](int y) {
    float max_rg = 0.0f, max_b = 0.0f;
    const float py = cell_coord_from_texel(y, n, spec.period);
    for (int x = 0; x < n; ++x) {
      const float px = cell_coord_from_texel(x, n, spec.period);
      const glm::vec2 v = curl2({px, py}, period2, spec.octaves, spec.seed, spec.gain);
      float* t = tex.texel(x, y);
      t[0] = v.x;
      t[1] = v.y;
      max_rg = std::max({max_rg, std::abs(t[0]), std::abs(t[1])});
      if (!spec.with_z) continue;
      // z of curl3 = d psi2 / dx - d psi1 / dy; the other potential is not needed.
      const glm::vec3 p3(px, py, spec.slice_z);
      const glm::vec3 d1 = curl3_potential(0, p3, period3, spec.octaves, seed3, spec.gain).gradient;
      const glm::vec3 d2 = curl3_potential(1, p3, period3, spec.octaves, seed3, spec.gain).gradient;
      t[2] = d2.x - d1.y;
      max_b = std::max(max_b, std::abs(t[2]));
    }
    row_max_rg[y] = max_rg;
    row_max_b[y] = max_b;
    progress.tick();
  });
  const float scale_rg = *std::max_element(row_max_rg.begin(), row_max_rg.end());
  const float scale_b = *std::max_element(row_max_b.begin(), row_max_b.end());
  for (size_t i = 0; i < tex.data.size(); i += size_t(nc)) {
    tex.data[i] = curl_texel_from_value(tex.data[i], scale_rg);
    tex.data[i + 1] = curl_texel_from_value(tex.data[i + 1], scale_rg);
    if (spec.with_z) tex.data[i + 2] = curl_texel_from_value(tex.data[i + 2], scale_b);
  }

  Metadata& m = tex.metadata;
  set_meta(m, "product", "curl");
  set_meta(m, "seed", int(spec.seed));  // at most 2^31 - 1 (the schemas): an int
  set_meta(m, "tiling", "periodic on x, y");
  set_meta(m, "period", spec.period);
  set_meta(m, "octaves", spec.octaves);
  set_meta(m, "gain", double(spec.gain));
  set_meta(m, "slice_z", double(spec.slice_z));
  set_meta(m, "curl_scale_rg", double(scale_rg));
  if (spec.with_z) set_meta(m, "curl_scale_b", double(scale_b));
  set_meta(m, "encoding", "v = (2 * c - 1) * curl_scale, per lattice cell of the base period");
  set_meta(m, "channel.R", "2D curl x: d psi / dy of a periodic Perlin fBm potential");
  set_meta(m, "channel.G", "2D curl y: -d psi / dx");
  if (spec.with_z)
    set_meta(m, "channel.B", "3D curl z on the plane z = slice_z (independent potentials)");
  return tex;
}

}  // namespace skybake

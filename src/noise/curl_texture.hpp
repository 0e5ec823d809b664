// The tileable curl noise texture (docs/reference.md "Cloud noise"): 128^2
// RGB, the size and channel count of Schneider & Vos's SIGGRAPH 2015 slides,
// used by the GPU Pro 7
// sampler (sec. 4.3.4) to distort the detail-noise lookups
// ("p.xy += curl_noise.xy * (1.0 - height_fraction)").
//
//   R, G  the 2D curl (d psi / dy, -d psi / dx) of a periodic Perlin fBm
//         potential (curl.hpp): divergence free in the plane, which is the
//         part Schneider's sampler reads.
//   B     the z component of the 3D curl noise (curl3) on the plane
//         z = slice_z, for shaders that also distort vertically. Its own
//         potentials (seeded independently of R, G), same period and octaves.
//
// Encoding: c = 0.5 + 0.5 v / curl_scale, with curl_scale the largest |R| or
// |G| of this bake for R and G (one scale, so directions are kept) and the
// largest |B| for B. The scales are exact maxima, so every channel spans
// [0, 1] without clamping, a uniform scale keeps the field divergence free,
// and shaders decode v = (2 c - 1) * curl_scale with the "curl_scale_rg" and
// "curl_scale_b" metadata (v per lattice cell of the base period).
// Threading: tbb::parallel_for over rows; identical output for any thread count.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "noise/noise_volume.hpp"

namespace skybake {

struct CurlSpec {
  int size = 128;        // texels per axis (square)
  uint32_t seed = 0;     // any value
  int period = 4;        // lattice cells across the texture, first octave of the potential
  int octaves = 3;       // potential octaves: periods 4, 8, 16 (8 texels per finest cell)
  float gain = 0.5f;     // amplitude ratio between potential octaves, (0, 1]
  float slice_z = 0.5f;  // B: plane of the 3D curl, lattice cells (mid-cell: off the lattice plane)
  bool with_z = true;     // bake B; false: R, G only (two-channel formats such as BC5, R8G8)
};

std::vector<SpecProblem> spec_problems(const CurlSpec& spec);

// One component's encoding with its scale (the largest |v| of the bake; 0 for
// a field that is 0 everywhere) and the decode shaders apply
// (runtime/glsl/clouds_noise.glsl has both under the same names). Clamped:
// v * (0.5 / scale) can round one ulp past 0.5 at the maximum.
inline float curl_texel_from_value(float v, float scale) {
  const float k = scale > 0.0f ? 0.5f / scale : 0.0f;
  return std::clamp(0.5f + v * k, 0.0f, 1.0f);
}
inline float curl_value_from_texel(float c, float scale) {
  return (2.0f * c - 1.0f) * scale;
}

// Channels "R", "G", "B" ("R", "G" without with_z); metadata: product, seed,
// period, octaves, gain, curl_scale_rg, curl_scale_b (with B), encoding,
// channel meanings.
Texture bake_curl(const CurlSpec& spec, const BakeContext& ctx);

}  // namespace skybake

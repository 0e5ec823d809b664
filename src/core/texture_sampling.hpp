// Filtered reads of a Texture, the way a GPU samples the LUTs we bake:
// texel centres at (i + 0.5) / n, bilinear, clamp to edge (or wrap in u).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

// Bilinear filtering of slice z of `layer` at texture coordinates (u, v),
// clamp to edge in v, wrap or clamp in u. Returns the first min(4, channels)
// channels (the rest 0).
glm::dvec4 sample_bilinear(const Texture& tex, double u, double v, int z, int layer, bool wrap_u);

// One axis of a bilinear read: the two texels i0, i1 in [0, n) around the
// texture coordinate and the weight f of i1. A coordinate that is not finite
// reads the first texel, and a wrapped one is brought into [0, n) first: no
// index ever leaves the texture.
struct BilinearAxis {
  int i0, i1;
  double f;
};
inline BilinearAxis bilinear_axis(double coord, int n, bool wrap) {
  double x = coord * n - 0.5;
  if (!std::isfinite(x)) x = 0.0;
  if (wrap) x -= n * std::floor(x / n);
  else x = std::clamp(x, 0.0, double(n - 1));
  const double x0 = std::floor(x);
  if (wrap) return {wrap_index(int(x0), n), wrap_index(int(x0) + 1, n), x - x0};
  return {int(x0), std::min(int(x0) + 1, n - 1), x - x0};
}

// The v half of sample_bilinear, done once for many reads at one v (a row of
// lookups at one radius): the two rows of texels and the weight between them.
struct BilinearRow {
  const float* row0;  // texel (0, y0)
  const float* row1;  // texel (0, y1)
  double fy;
  int channels;
};
inline BilinearRow bilinear_row(const Texture& tex, double v, int z, int layer) {
  const BilinearAxis a = bilinear_axis(v, tex.height, false);
  return {tex.texel(0, a.i0, z, layer), tex.texel(0, a.i1, z, layer), a.f, tex.channel_count()};
}

// The first three channels of sample_bilinear(tex, u, v, z, layer, false) for
// the row's v, bit for bit (the same operations in the same order); the
// texture must have at least three channels.
inline glm::dvec3 sample_bilinear_rgb(const Texture& tex, const BilinearRow& row, double u) {
  const BilinearAxis a = bilinear_axis(u, tex.width, false);
  const float* t00 = row.row0 + size_t(a.i0) * row.channels;
  const float* t10 = row.row0 + size_t(a.i1) * row.channels;
  const float* t01 = row.row1 + size_t(a.i0) * row.channels;
  const float* t11 = row.row1 + size_t(a.i1) * row.channels;
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    const double lo = t00[c] + a.f * (double(t10[c]) - t00[c]);
    const double hi = t01[c] + a.f * (double(t11[c]) - t01[c]);
    out[c] = lo + row.fy * (hi - lo);
  }
  return out;
}

}  // namespace skybake

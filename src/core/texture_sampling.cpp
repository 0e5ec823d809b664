#include "core/texture_sampling.hpp"

#include <algorithm>
#include <cmath>

#include "core/math.hpp"

namespace skybake {

glm::dvec4 sample_bilinear(const Texture& tex, double u, double v, int z, int layer, bool wrap_u) {
  const BilinearAxis ax = bilinear_axis(u, tex.width, wrap_u);
  const BilinearAxis ay = bilinear_axis(v, tex.height, false);
  const int nc = std::min(tex.channel_count(), 4);
  glm::dvec4 out(0.0);
  const float* t00 = tex.texel(ax.i0, ay.i0, z, layer);
  const float* t10 = tex.texel(ax.i1, ay.i0, z, layer);
  const float* t01 = tex.texel(ax.i0, ay.i1, z, layer);
  const float* t11 = tex.texel(ax.i1, ay.i1, z, layer);
  for (int c = 0; c < nc; ++c) {
    const double a = t00[c] + ax.f * (double(t10[c]) - t00[c]);
    const double b = t01[c] + ax.f * (double(t11[c]) - t01[c]);
    out[c] = a + ay.f * (b - a);
  }
  return out;
}

}  // namespace skybake

#include "core/texture_sampling.hpp"

#include <algorithm>
#include <cmath>

#include "core/math.hpp"

namespace skybake {

glm::dvec4 sample_bilinear(const Texture& tex, double u, double v, int z, int layer, bool wrap_u) {
  const auto axis = [](double coord, int n, bool wrap, int& i0, int& i1, double& f) {
    double x = coord * n - 0.5;
    // A coordinate that is not finite reads the first texel, and a wrapped
    // one is brought into [0, n) first: no index ever leaves the texture.
    if (!std::isfinite(x)) x = 0.0;
    if (wrap) x -= n * std::floor(x / n);
    else x = std::clamp(x, 0.0, double(n - 1));
    const double x0 = std::floor(x);
    f = x - x0;
    if (wrap) {
      i0 = wrap_index(int(x0), n);
      i1 = wrap_index(int(x0) + 1, n);
    } else {
      i0 = int(x0);
      i1 = std::min(i0 + 1, n - 1);
    }
  };
  int x0, x1, y0, y1;
  double fx, fy;
  axis(u, tex.width, wrap_u, x0, x1, fx);
  axis(v, tex.height, false, y0, y1, fy);
  const int nc = std::min(tex.channel_count(), 4);
  glm::dvec4 out(0.0);
  const float* t00 = tex.texel(x0, y0, z, layer);
  const float* t10 = tex.texel(x1, y0, z, layer);
  const float* t01 = tex.texel(x0, y1, z, layer);
  const float* t11 = tex.texel(x1, y1, z, layer);
  for (int c = 0; c < nc; ++c) {
    const double a = t00[c] + fx * (double(t10[c]) - t00[c]);
    const double b = t01[c] + fx * (double(t11[c]) - t01[c]);
    out[c] = a + fy * (b - a);
  }
  return out;
}

}  // namespace skybake

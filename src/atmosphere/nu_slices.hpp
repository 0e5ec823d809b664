// A scattering order read along one (r, mu, mu_s) with only nu turning: the
// table blended over r, mu and mu_s once, one value per nu slice (per group
// for order 1), so each nu lerps two slices instead of a quadrilinear read
// with its mapping. The same sum as ScatteringOrder::radiance_at, its terms
// grouped by slice (equal to rounding: tests/atmosphere/irradiance_lut_test.cpp
// and scattering_orders_test.cpp compare with one read per direction).
// Used where many directions share a zenith angle: the density's incident
// field (incident_radiance.cpp) and the indirect irradiance (irradiance_lut.cpp).
#pragma once

#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/scattering_lut.hpp"
#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

struct NuSlices {
  std::vector<glm::dvec3> first, second;  // radiance, or S_R and S_M for order 1

  static void blend(const Texture& table, const ScatteringShape& shape, const ScatteringTaps& t,
                    std::vector<glm::dvec3>& out) {
    out.assign(shape.nu_size, glm::dvec3(0.0));
    const int r_i[2] = {t.r.i0, t.r.i1}, mu_i[2] = {t.mu.i0, t.mu.i1};
    const int mus_i[2] = {t.mu_s.i0, t.mu_s.i1};
    const double r_w[2] = {1.0 - t.r.w, t.r.w}, mu_w[2] = {1.0 - t.mu.w, t.mu.w};
    const double mus_w[2] = {1.0 - t.mu_s.w, t.mu_s.w};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int m = 0; m < 2; ++m) {
          const double w = r_w[a] * mu_w[b] * mus_w[m];
          if (w == 0.0) continue;
          const float* row = table.texel(mus_i[m], mu_i[b], r_i[a]);
          const int stride = table.channel_count() * shape.mu_s_size;
          for (int n = 0; n < shape.nu_size; ++n)
            for (int c = 0; c < 3; ++c) out[n][c] += w * row[n * stride + c];
        }
  }
  // The slices at the r, mu and mu_s taps of t (its nu tap is not used).
  void read(const ScatteringOrder& order, const ScatteringShape& shape, const ScatteringTaps& t) {
    if (order.radiance) {
      blend(*order.radiance, shape, t, first);
      return;
    }
    if (order.phases->has_rayleigh) blend(*order.rayleigh, shape, t, first);
    if (order.phases->has_mie) blend(*order.mie, shape, t, second);
  }
  // ScatteringOrder::radiance_at at nu.
  glm::dvec3 radiance_at_nu(const ScatteringOrder& order, const ScatteringShape& shape,
                            double nu) const {
    // scattering_taps' nu tap of the mapping's u_nu.
    const AxisTap tn = nu_slice_tap(0.5 * (clamp_cosine(nu) + 1.0), shape.nu_size);
    auto lerp = [&](const std::vector<glm::dvec3>& s) {
      return (1.0 - tn.w) * s[tn.i0] + tn.w * s[tn.i1];
    };
    if (order.radiance) return lerp(first);
    glm::dvec3 L(0.0);
    if (order.phases->has_rayleigh) L += order.phases->rayleigh(nu) * lerp(first);
    if (order.phases->has_mie) L += order.phases->mie(nu) * lerp(second);
    return L;
  }
};

}  // namespace skybake

// The density's table in the sun's frame: its views and its reference
// read. See the header.
#include "atmosphere/sun_frame_density.hpp"

#include <algorithm>
#include <cmath>

#include "core/math.hpp"

namespace skybake {

std::vector<double> sun_frame_nu_grid(int nu_size) {
  std::vector<double> nodes;
  for (int k = 0; k < nu_size; ++k) {
    const double nu = -1.0 + 2.0 * k / (nu_size - 1);
    nodes.push_back(nu);
    if (k + 1 == nu_size) break;
    // The angles between this slice and the next, in equal steps.
    const double from = std::acos(nu), to = std::acos(-1.0 + 2.0 * (k + 1) / (nu_size - 1));
    for (int j = 1; j < kSunFrameNuSteps; ++j)
      nodes.push_back(std::cos(from + (to - from) * j / kSunFrameNuSteps));
  }
  return nodes;
}

AxisTap sun_frame_nu_tap(const std::vector<double>& grid, double nu) {
  const int n = int(grid.size());
  const double v = std::clamp(nu, grid.front(), grid.back());
  // The last node at or below v.
  const int i0 = std::clamp(int(std::upper_bound(grid.begin(), grid.end(), v) - grid.begin()) - 1,
                            0, n - 1);
  if (i0 == n - 1 || grid[i0] == v) return {i0, i0, 0.0};
  return {i0, i0 + 1, (v - grid[i0]) / (grid[i0 + 1] - grid[i0])};
}

glm::dvec3 sun_frame_view(double mu_s, double nu, double cos_phi) {
  const double sin_s = safe_sqrt(1.0 - mu_s * mu_s), sin_nu = safe_sqrt(1.0 - nu * nu);
  const double sin_phi = safe_sqrt(1.0 - cos_phi * cos_phi);
  return {nu * sin_s - sin_nu * cos_phi * mu_s, sin_nu * sin_phi,
          nu * mu_s + sin_nu * cos_phi * sin_s};
}

double sun_frame_cos_phi_of(double mu, double mu_s, double nu) {
  const double den = safe_sqrt(1.0 - nu * nu) * safe_sqrt(1.0 - mu_s * mu_s);
  if (!(den > 1e-12)) return 1.0;
  return std::clamp((mu - nu * mu_s) / den, -1.0, 1.0);
}

glm::dvec3 lookup_sun_frame_density(const SunFrameDensity& J, const MuSAxis& mu_s_axis,
                                    const AxisTap& r_tap, double mu, double mu_s, double nu) {
  const ScatteringShape& shape = J.shape;
  const AxisTap tl = mu_s_axis.tap(mu_s);
  const AxisTap tn = sun_frame_nu_tap(J.nu, clamp_cosine(nu));
  const double t = 0.5 * (1.0 - sun_frame_cos_phi_of(mu, clamp_cosine(mu_s), nu)) *
                   (J.phi_size - 1);
  const int p0 = std::min(int(t), J.phi_size - 2);
  const double pw = t - p0;
  const int z[2] = {r_tap.i0, r_tap.i1}, m[2] = {tn.i0, tn.i1}, l[2] = {tl.i0, tl.i1};
  const double zw[2] = {1.0 - r_tap.w, r_tap.w}, mw[2] = {1.0 - tn.w, tn.w};
  const double lw[2] = {1.0 - tl.w, tl.w}, w_p[2] = {1.0 - pw, pw};
  glm::dvec3 sum(0.0);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c)
        for (int d = 0; d < 2; ++d) {
          const double w = zw[a] * mw[b] * lw[c] * w_p[d];
          if (w == 0.0) continue;
          const Rgb4& v = J.texels[J.index(z[a], m[b], l[c], p0 + d)];
          sum += w * glm::dvec3(v.v[0], v.v[1], v.v[2]);
        }
  return sum;
}

}  // namespace skybake

// The 4D table's error between mu texels on its second order. See the header.
#include "atmosphere/mid_texel_error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "atmosphere/multiple_scattering.hpp"

namespace skybake {

namespace {

struct MidSample {
  glm::dvec3 direct{0.0}, read{0.0};
};

// DeltaS_2 at (r, mu, mu_s, nu) by the quadrature and by the table's read.
MidSample mid_sample(const Atmosphere& atm, const SunFrameDensity& J, const Texture& delta,
                     int nodes, const ScatteringParams& p, double nu) {
  MidSample s;
  s.direct = compute_multiple_scattering(atm, J, p.r, p.mu, p.mu_s, nu, p.ray_hits_ground, nodes);
  s.read = lookup_scattering_rgb(delta, J.shape, atm, p.r, p.mu, p.mu_s, nu, p.ray_hits_ground);
  return s;
}

// The samples of r texel z at mu coordinate u_mu: u_mu a midpoint between
// texels read at the nu slices, or a texel's centre read halfway between
// slices (each nu where the geometry allows it).
void mid_samples(const Atmosphere& atm, const SunFrameDensity& J, const Texture& delta,
                 int nodes, int z, double u_mu, bool nu_midpoints, std::vector<MidSample>& out) {
  const ScatteringShape& shape = J.shape;
  const double u_r = (z + 0.5) / shape.r_size;
  for (int l = 0; l < shape.mu_s_size; l += 8)
    for (int m = 0; m + (nu_midpoints ? 1 : 0) < shape.nu_size; m += nu_midpoints ? 1 : 4) {
      const double u_mu_s = (l + 0.5) / shape.mu_s_size;
      const double u_nu = (m + (nu_midpoints ? 0.5 : 0.0)) / (shape.nu_size - 1);
      const ScatteringParams p =
          r_mu_mu_s_nu_from_scattering_uvwz(atm, shape, {u_nu, u_mu_s, u_mu, u_r});
      const double spread = ScatteringTexelGrid::spread(p.mu, p.mu_s);
      const double nu = -1.0 + 2.0 * u_nu;
      if (nu < p.mu * p.mu_s - spread || nu > p.mu * p.mu_s + spread) continue;
      out.push_back(mid_sample(atm, J, delta, nodes, p, nu));
    }
}

}  // namespace

double mid_texel_error(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                       const Texture& delta, int nodes) {
  const ScatteringShape& shape = J_per_sigma_s.shape;
  const int half = shape.mu_size / 2;
  const int zs[2] = {0, shape.r_size / 2};
  // Per (r, midpoint) in parallel, gathered in order: the same value for
  // any thread count.
  std::vector<std::vector<MidSample>> rows(size_t(2 * shape.mu_size));
  tbb::parallel_for(0, 2 * shape.mu_size, [&](int i) {
    const int y = i % shape.mu_size, z = zs[i / shape.mu_size];
    // Between mu texels y and y + 1 (not across the horizon, nor past the
    // end); at texel y, between nu slices (every 8th texel).
    if (y + 1 != half && y + 1 != shape.mu_size)
      mid_samples(atm, J_per_sigma_s, delta, nodes, z, (y + 1.0) / shape.mu_size, false,
                  rows[size_t(i)]);
    if (y % 8 == 4)
      mid_samples(atm, J_per_sigma_s, delta, nodes, z, (y + 0.5) / shape.mu_size, true,
                  rows[size_t(i)]);
  });
  double peak = 0.0;
  for (const auto& row : rows)
    for (const MidSample& s : row) peak = std::max({peak, s.direct.r, s.direct.g, s.direct.b});
  double sum_sq = 0.0;
  size_t n = 0;
  for (const auto& row : rows)
    for (const MidSample& s : row)
      for (int c = 0; c < 3; ++c)
        if (s.direct[c] > 1e-3 * peak) {
          const double rel = s.read[c] / s.direct[c] - 1.0;
          sum_sq += rel * rel;
          ++n;
        }
  return n > 0 ? std::sqrt(sum_sq / double(n)) : 0.0;
}

}  // namespace skybake

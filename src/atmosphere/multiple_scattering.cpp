// DeltaS_k of the 4D table: J_k integrated along view rays, the direct
// quadrature and the fast path that shares a row's nodes and (r, mu) taps.
// See scattering_orders.hpp for the equations.
#include "atmosphere/multiple_scattering.hpp"

#include <algorithm>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "core/math.hpp"

namespace skybake {

Texture density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                               const Texture& density) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  std::vector<glm::dvec3> sigma_s(shape.r_size);
  for (int z = 0; z < shape.r_size; ++z)
    sigma_s[z] = sample_medium(atm, texels.r[z] - atm.bottom_radius_m).scattering;
  Texture out = density;
  for (int c = 0; c < 3; ++c)
    for (int z = 0; z < shape.r_size; ++z) {
      // Where sigma_s = 0 (a layer that ends at the top texel, r = Rt
      // exactly), J / sigma_s is undefined: take the nearest r texel's.
      int from = z;
      for (int k = 1; sigma_s[from][c] == 0.0 && k < shape.r_size; ++k)
        for (int candidate : {z - k, z + k})
          if (candidate >= 0 && candidate < shape.r_size && sigma_s[candidate][c] > 0.0 &&
              sigma_s[from][c] == 0.0)
            from = candidate;
      for (int y = 0; y < density.height; ++y)
        for (int x = 0; x < density.width; ++x)
          out.texel(x, y, z)[c] = sigma_s[from][c] > 0.0
                                      ? float(density.texel(x, y, from)[c] / sigma_s[from][c])
                                      : 0.0f;
    }
  return out;
}

glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                       const Texture& density_per_sigma_s, double r, double mu,
                                       double mu_s, double nu, bool ray_hits_ground, int nodes) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double d = distance_to_nearest_boundary(rb, rt, r, mu, ray_hits_ground);
  const Texture& radiance = density_per_sigma_s;
  RayTransfer transfer;
  ray_transfer(atm, r, mu, d, nodes, transfer);
  glm::dvec3 sum(0.0);
  for (const TransferNode& q : transfer.nodes) {
    const double mu_i = mu_after(r, mu, q.s, q.r);
    const double mu_s_i = clamp_cosine((r * mu_s + q.s * nu) / q.r);
    const glm::dvec3 sigma_s = sample_medium(atm, q.r - rb).scattering;
    sum += q.weight * sigma_s *
           lookup_scattering_rgb(radiance, shape, atm, q.r, mu_i, mu_s_i, nu, ray_hits_ground);
  }
  return sum;
}

Texture bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                 const Texture& density, int nodes, const BakeContext& ctx) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const MuSAxis mu_s_axis(atm, shape);
  const Texture radiance = density_per_scattering(atm, shape, density);
  const int W = shape.texture_width(), n_mu_s = shape.mu_s_size;
  Texture out(W, shape.mu_size, shape.r_size, 1, {"R", "G", "B"});
  const int rows = shape.r_size * shape.mu_size;
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RayTransfer transfer;
    std::vector<double> slice(3 * size_t(W)), sum(3 * size_t(W));
    // Per texel of the row: its mu_s and nu (nu is constant along the ray,
    // and so are its slice taps); per node, the texels' mu_s there and
    // their mu_s taps, computed for the whole row in one branch-free pass.
    std::vector<double> mu_s_x(W), nu_x(W), mu_s_node(W), tap_w(W);
    std::vector<int> tap_i0(W);
    std::vector<AxisTap> nu_taps(W);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int z = row / shape.mu_size, y = row % shape.mu_size;
      ScatteringParams p0;
      for (int x = 0; x < W; ++x) {
        const ScatteringParams p = texels.at(x, y, z);
        if (x == 0) p0 = p;
        mu_s_x[x] = p.mu_s;
        nu_x[x] = p.nu;
        nu_taps[x] = scattering_taps(shape, {0.5 * (p.nu + 1.0), 0.5, 0.5, 0.5}).nu;
      }
      const double r = p0.r, mu = p0.mu;
      const bool hits = p0.ray_hits_ground;
      ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, hits), nodes, transfer);
      std::fill(sum.begin(), sum.end(), 0.0);
      for (const TransferNode& q : transfer.nodes) {
        const glm::dvec3 wS = q.weight * sample_medium(atm, q.r - rb).scattering;
        if (wS == glm::dvec3(0.0)) continue;
        const double r_i = q.r, mu_i = mu_after(r, mu, q.s, r_i);
        const glm::dvec4 uvwz =
            scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r_i, mu_i, 1.0, 1.0, hits);
        // J / sigma_s at (r_i, mu_i) for every (mu_s, nu) texel: the
        // bilinear blend of four rows of the table, shared by the row's W
        // texels.
        const AxisTap tr = axis_tap(uvwz.w, shape.r_size), tm = axis_tap(uvwz.z, shape.mu_size);
        const float* rows4[4] = {radiance.texel(0, tm.i0, tr.i0), radiance.texel(0, tm.i1, tr.i0),
                                 radiance.texel(0, tm.i0, tr.i1), radiance.texel(0, tm.i1, tr.i1)};
        const double w4[4] = {(1.0 - tr.w) * (1.0 - tm.w), (1.0 - tr.w) * tm.w, tr.w * (1.0 - tm.w),
                              tr.w * tm.w};
        for (size_t i = 0; i < slice.size(); ++i)
          slice[i] =
              w4[0] * rows4[0][i] + w4[1] * rows4[1][i] + w4[2] * rows4[2][i] + w4[3] * rows4[3][i];
        // clamp_cosine as min / max: the same value, no branch.
        for (int x = 0; x < W; ++x)
          mu_s_node[x] = std::min(std::max((r * mu_s_x[x] + q.s * nu_x[x]) / r_i, -1.0), 1.0);
        mu_s_axis.taps(mu_s_node.data(), W, tap_i0.data(), tap_w.data());
        for (int x = 0; x < W; ++x) {
          const AxisTap tn = nu_taps[x];
          const int l0 = tap_i0[x];
          const double lw = tap_w[x];
          const double* s00 = &slice[3 * size_t(tn.i0 * n_mu_s + l0)];
          const double* s10 = &slice[3 * size_t(tn.i1 * n_mu_s + l0)];
          for (int c = 0; c < 3; ++c) {
            const double L = (1.0 - tn.w) * ((1.0 - lw) * s00[c] + lw * s00[3 + c]) +
                             tn.w * ((1.0 - lw) * s10[c] + lw * s10[3 + c]);
            sum[3 * size_t(x) + c] += wS[c] * L;
          }
        }
      }
      float* texels_out = out.texel(0, y, z);
      for (size_t i = 0; i < sum.size(); ++i) texels_out[i] = float(sum[i]);
      progress.tick();
    }
  });
  return out;
}

}  // namespace skybake

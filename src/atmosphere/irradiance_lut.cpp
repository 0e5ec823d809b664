// Ground irradiance: mapping, direct and indirect terms. See the header
// (Bruneton 2017 functions.glsl "Ground irradiance").
#include "atmosphere/irradiance_lut.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/nu_slices.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

void check_irradiance_size(int width, int height) {
  if (width < 2 || height < 2)
    throw Error(
        fmt::format("irradiance table: expected at least 2x2 texels, got {}x{}", width, height));
}

template <class F>
Texture bake_irradiance_table(const Atmosphere& atm, int width, int height, const BakeContext& ctx,
                              F&& irradiance) {
  check_irradiance_size(width, height);
  Texture tex(width, height, 1, 1, {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(height));
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < width; ++x) {
        double r = 0.0, mu_s = 0.0;
        r_mu_s_from_irradiance_uv(atm, {texel_center(x, width), texel_center(y, height)}, width,
                                  height, r, mu_s);
        const glm::dvec3 E = irradiance(r, mu_s);
        float* texel = tex.texel(x, y);
        for (int c = 0; c < 3; ++c) texel[c] = float(E[c]);
      }
      progress.tick();
    }
  });
  return tex;
}

}  // namespace

glm::dvec2 irradiance_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                     int height) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double x_r = std::clamp((r - rb) / (rt - rb), 0.0, 1.0);
  const double x_mu_s = 0.5 * clamp_cosine(mu_s) + 0.5;
  return {texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_r, height)};
}

void r_mu_s_from_irradiance_uv(const Atmosphere& atm, glm::dvec2 uv, int width, int height,
                               double& r, double& mu_s) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double x_mu_s = std::clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0);
  const double x_r = std::clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  r = rb + x_r * (rt - rb);
  mu_s = clamp_cosine(2.0 * x_mu_s - 1.0);
}

double sun_average_cosine(double mu_s, double alpha) {
  // A disk of angular radius alpha crossing the horizon: the cosine factor
  // averaged over it, approximated as in Bruneton 2017 by the quadratic that
  // joins 0 at -alpha to mu_s at +alpha with a matching slope.
  if (!(alpha > 0.0)) return std::max(mu_s, 0.0);  // a point sun
  if (mu_s < -alpha) return 0.0;
  if (mu_s > alpha) return mu_s;
  return (mu_s + alpha) * (mu_s + alpha) / (4.0 * alpha);
}

glm::dvec3 compute_direct_irradiance(const Atmosphere& atm, const Texture& transmittance_lut,
                                     double r, double mu_s) {
  const double c = sun_average_cosine(mu_s, atm.sun_angular_radius_rad);
  if (c == 0.0) return glm::dvec3(0.0);
  return atm.sun_illuminance * lookup_transmittance_to_top(transmittance_lut, atm, r, mu_s) * c;
}

glm::dvec3 compute_indirect_irradiance(const Atmosphere& atm, const ScatteringShape& shape,
                                       const ScatteringOrder& order, double r, double mu_s,
                                       int directions) {
  const int bands = std::max(1, directions / 2), azimuths = std::max(1, directions);
  const double d_theta = 0.5 * kPi / bands, d_phi = kPi / azimuths;
  // The sun in the x-z plane; the sky is symmetric about it (phi -> -phi).
  const double sun_x = std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s));
  // The azimuths' cosines once per texel, not per band: std::cos in the
  // band loop was a tenth of a small 4D field's bake.
  thread_local std::vector<double> cos_phi;
  cos_phi.resize(size_t(azimuths));
  for (int m = 0; m < azimuths; ++m) cos_phi[size_t(m)] = std::cos((m + 0.5) * d_phi);
  glm::dvec3 E(0.0);
  NuSlices slices;
  for (int l = 0; l < bands; ++l) {
    const double theta0 = l * d_theta, theta1 = (l + 1) * d_theta, theta = (l + 0.5) * d_theta;
    // int_band cos(theta) sin(theta) d theta, times 2 d_phi for the mirrored half.
    const double s0 = std::sin(theta0), s1 = std::sin(theta1);
    const double weight = 0.5 * (s1 * s1 - s0 * s0) * 2.0 * d_phi;
    const double mu = std::cos(theta), sin_theta = std::sin(theta);
    // r, mu and mu_s are the band's for every azimuth; only nu turns.
    slices.read(order, shape,
                scattering_taps(shape, scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s,
                                                                         1.0, false)));
    for (int m = 0; m < azimuths; ++m) {
      const double nu = sin_theta * cos_phi[size_t(m)] * sun_x + mu * mu_s;
      E += weight * slices.radiance_at_nu(order, shape, nu);
    }
  }
  return E;
}

Texture bake_direct_irradiance(const Atmosphere& atm, const Texture& transmittance_lut, int width,
                               int height, const BakeContext& ctx) {
  return bake_irradiance_table(atm, width, height, ctx, [&](double r, double mu_s) {
    return compute_direct_irradiance(atm, transmittance_lut, r, mu_s);
  });
}

Texture bake_indirect_irradiance(const Atmosphere& atm, const ScatteringShape& shape,
                                 const ScatteringOrder& order, int width, int height,
                                 int directions, const BakeContext& ctx) {
  return bake_irradiance_table(atm, width, height, ctx, [&](double r, double mu_s) {
    return compute_indirect_irradiance(atm, shape, order, r, mu_s, directions);
  });
}

glm::dvec3 lookup_irradiance(const Texture& table, const Atmosphere& atm, double r, double mu_s) {
  const glm::dvec2 uv = irradiance_uv_from_r_mu_s(atm, r, mu_s, table.width, table.height);
  const AxisTap tx = axis_tap(uv.x, table.width), ty = axis_tap(uv.y, table.height);
  glm::dvec3 out(0.0);
  for (int c = 0; c < 3; ++c) {
    const double bottom =
        table.at(tx.i0, ty.i0, 0, 0, c) * (1.0 - tx.w) + table.at(tx.i1, ty.i0, 0, 0, c) * tx.w;
    const double top =
        table.at(tx.i0, ty.i1, 0, 0, c) * (1.0 - tx.w) + table.at(tx.i1, ty.i1, 0, 0, c) * tx.w;
    out[c] = bottom * (1.0 - ty.w) + top * ty.w;
  }
  return out;
}

}  // namespace skybake

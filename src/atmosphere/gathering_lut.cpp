// Gathering LUT of the azimuth-free table. See the header (Bodare &
// Sandberg 2014 sec. 4.7.3).
#include "atmosphere/gathering_lut.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

glm::dvec3 GroundLight3d::irradiance(const Atmosphere& atm, const Texture& transmittance_lut,
                                     double mu_s) const {
  if (!per_sun_texel)
    return compute_direct_irradiance(atm, transmittance_lut, atm.bottom_radius_m, mu_s);
  const std::vector<glm::dvec3>& E = *per_sun_texel;
  const int n = int(E.size());
  const AxisTap t = axis_tap(scattering3d_u_from_mu_s(mu_s, n), n);
  return (1.0 - t.w) * E[t.i0] + t.w * E[t.i1];
}

GatheringWeights gathering_weights(const ScatteringPhases& phases, double mu_s, int bands) {
  constexpr int kSubBands = 8, kAzimuths = 256;
  GatheringWeights w;
  for (auto* v : {&w.sphere_rayleigh, &w.sphere_mie, &w.cosine_rayleigh, &w.cosine_mie})
    v->assign(bands, 0.0);
  const double sin_s = safe_sqrt(1.0 - mu_s * mu_s), d_theta = kPi / (bands * kSubBands);
  const double d_phi = kPi / kAzimuths;  // half circle, twice the weight
  for (int l = 0; l < bands; ++l)
    for (int k = 0; k < kSubBands; ++k) {
      const int sub = l * kSubBands + k;
      const double theta = (sub + 0.5) * d_theta, mu = std::cos(theta), sin_t = std::sin(theta);
      const double area = 2.0 * d_phi * (std::cos(sub * d_theta) - std::cos((sub + 1) * d_theta));
      double p_r = 0.0, p_m = 0.0;
      for (int m = 0; m < kAzimuths; ++m) {
        const double nu = mu * mu_s + sin_t * sin_s * std::cos((m + 0.5) * d_phi);
        if (phases.has_rayleigh) p_r += phases.rayleigh(nu);
        if (phases.has_mie) p_m += phases.mie(nu);
      }
      w.sphere_rayleigh[l] += area * p_r;
      w.sphere_mie[l] += area * p_m;
      if (mu > 0.0) {
        w.cosine_rayleigh[l] += area * mu * p_r;
        w.cosine_mie[l] += area * mu * p_m;
      }
    }
  double sum_r = 0.0, sum_m = 0.0;
  for (int l = 0; l < bands; ++l) {
    sum_r += w.sphere_rayleigh[l];
    sum_m += w.sphere_mie[l];
  }
  for (int l = 0; l < bands; ++l) {
    if (sum_r > 0.0) w.sphere_rayleigh[l] /= sum_r;
    if (sum_m > 0.0) w.sphere_mie[l] /= sum_m;
  }
  return w;
}

namespace {

Gathering gather(const Atmosphere& atm, const Texture& transmittance_lut,
                 const Scattering3dShape& shape, const Scattering3dOrder& order,
                 const GroundLight3d& ground, const GatheringWeights& weights, double h,
                 double mu_s, int bands) {
  const ScatteringPhases& phases = *order.phases;
  const double rb = atm.bottom_radius_m, r = rb + h;
  const double sin_s = safe_sqrt(1.0 - mu_s * mu_s);
  const glm::dvec3 albedo_over_pi = atm.ground_albedo / kPi;
  const bool ground_reflects = atm.ground_albedo != glm::dvec3(0.0);
  const double d_theta = kPi / bands, d_phi = kPi / bands;  // bands azimuths over half a circle
  Gathering out;
  for (int l = 0; l < bands; ++l) {
    // The band's sky and ground, sub-stepped near the horizon (band_parts).
    const std::vector<BandPart> parts =
        band_parts(atm, r, l * d_theta, (l + 1) * d_theta, ground_reflects);
    glm::dvec3 S_r(0.0), S_m(0.0);
    for (const BandPart& p : parts) {
      const double mu = std::cos(p.theta);
      if (phases.has_rayleigh)
        S_r += p.share * lookup_scattering3d_rgb(*order.rayleigh, shape, atm, h, mu, mu_s, p.hits);
      if (phases.has_mie)
        S_m += p.share * lookup_scattering3d_rgb(*order.mie, shape, atm, h, mu, mu_s, p.hits);
    }
    out.gathered += weights.sphere_rayleigh[l] * S_r + weights.sphere_mie[l] * S_m;
    out.ground += weights.cosine_rayleigh[l] * S_r + weights.cosine_mie[l] * S_m;
    if (!ground_reflects) continue;
    // The lit ground seen along the band's rays, azimuth by azimuth.
    const double cell = 2.0 * d_phi * (std::cos(l * d_theta) - std::cos((l + 1) * d_theta));
    for (const BandPart& p : parts) {
      if (!p.hits) continue;
      const double mu = std::cos(p.theta), sin_t = std::sin(p.theta);
      for (int m = 0; m < bands; ++m) {
        const double nu = mu * mu_s + sin_t * sin_s * std::cos((m + 0.5) * d_phi);
        const double mu_s_ground = clamp_cosine((r * mu_s + p.d * nu) / rb);
        out.gathered += p.share * cell * p.T_ground * albedo_over_pi *
                        ground.irradiance(atm, transmittance_lut, mu_s_ground);
      }
    }
  }
  return out;
}

}  // namespace

Gathering compute_gathering(const Atmosphere& atm, const Texture& transmittance_lut,
                            const Scattering3dShape& shape, const Scattering3dOrder& order,
                            const GroundLight3d& ground, double h, double mu_s, int bands) {
  return gather(atm, transmittance_lut, shape, order, ground,
                gathering_weights(*order.phases, mu_s, bands), h, mu_s, bands);
}

GatheringPass bake_gathering(const Atmosphere& atm, const Texture& transmittance_lut,
                             const Scattering3dShape& shape, const Scattering3dOrder& order,
                             const GroundLight3d& ground, int bands, const BakeContext& ctx) {
  check_scattering3d_shape(shape);
  if (bands < 2 || bands % 2 != 0)
    throw Error(fmt::format("gathering: expected an even number of bands >= 2, got {}", bands));
  GatheringPass out{Texture(shape.height_size, shape.sun_size, 1, 1, {"R", "G", "B"}),
                    std::vector<glm::dvec3>(shape.sun_size)};
  std::vector<GatheringWeights> weights(shape.sun_size);
  tbb::parallel_for(0, shape.sun_size, [&](int y) {
    weights[y] = gathering_weights(
        *order.phases, mu_s_from_scattering3d_u(texel_center(y, shape.sun_size), shape.sun_size),
        bands);
  });
  const int texels = shape.height_size * shape.sun_size;
  ProgressCounter progress(ctx, size_t(texels));
  tbb::parallel_for(tbb::blocked_range<int>(0, texels), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i != range.end(); ++i) {
      const int x = i % shape.height_size, y = i / shape.height_size;
      const double h =
          h_from_scattering3d_u(atm, texel_center(x, shape.height_size), shape.height_size);
      const double mu_s = mu_s_from_scattering3d_u(texel_center(y, shape.sun_size), shape.sun_size);
      const Gathering g =
          gather(atm, transmittance_lut, shape, order, ground, weights[y], h, mu_s, bands);
      float* texel = out.gathering.texel(x, y);
      for (int c = 0; c < 3; ++c) texel[c] = float(g.gathered[c]);
      if (x == 0) out.ground_irradiance[y] = g.ground;  // h = 0 exactly (texel centre)
      progress.tick();
    }
  });
  return out;
}

glm::dvec3 lookup_gathering(const Texture& gathering, const Atmosphere& atm, double h,
                            double mu_s) {
  const AxisTap tx = axis_tap(scattering3d_u_from_h(atm, h, gathering.width), gathering.width);
  const AxisTap ty = axis_tap(scattering3d_u_from_mu_s(mu_s, gathering.height), gathering.height);
  glm::dvec3 out(0.0);
  for (int c = 0; c < 3; ++c) {
    const double bottom = gathering.at(tx.i0, ty.i0, 0, 0, c) * (1.0 - tx.w) +
                          gathering.at(tx.i1, ty.i0, 0, 0, c) * tx.w;
    const double top = gathering.at(tx.i0, ty.i1, 0, 0, c) * (1.0 - tx.w) +
                       gathering.at(tx.i1, ty.i1, 0, 0, c) * tx.w;
    out[c] = bottom * (1.0 - ty.w) + top * ty.w;
  }
  return out;
}

}  // namespace skybake

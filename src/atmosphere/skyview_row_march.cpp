#include "atmosphere/skyview_row_march.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// The medium at altitude h: every component with extinction adds to sigma_t,
// the scattering ones to sigma_s and their densities to `densities`.
glm::dvec3 row_medium(const Atmosphere& atm, double h, SkyviewRowSegment& seg,
                      std::vector<double>& densities,
                      const std::vector<const MediumComponent*>& scattering) {
  glm::dvec3 sigma_t(0.0);
  for (const MediumComponent& c : atm.components) {
    if (c.density.layers.empty()) continue;
    const double d = density_at(c.density, h);
    sigma_t += d * (c.scattering_per_m + c.absorption_per_m);
  }
  for (const MediumComponent* c : scattering) {
    const double d = density_at(c->density, h);
    densities.push_back(d);
    seg.sigma_s += d * c->scattering_per_m;
  }
  return sigma_t;
}

}  // namespace

SkyviewRowMarch march_skyview_row(const Atmosphere& atm, const Texture& transmittance_lut,
                                  const Texture& multiscattering_lut,
                                  const MultiscatteringMapping& mapping, double r, double mu,
                                  int steps, StepDistribution distribution) {
  SkyviewRowMarch row;
  for (const MediumComponent& c : atm.components)
    if (c.scattering_per_m != glm::dvec3(0.0) && !c.density.layers.empty())
      row.components.push_back(&c);
  const double sin_theta = safe_sqrt(1.0 - mu * mu);
  const glm::dvec3 dir(sin_theta, 0.0, clamp_cosine(mu));
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, {0.0, 0.0, r}, dir);
  if (!span.hits_atmosphere || !(span.t_exit > span.t_enter)) return row;
  // The segment boundaries of sky_integrator's march.
  const int n = std::max(steps, 1);
  const double t0 = span.t_enter, t1 = span.t_exit;
  glm::dvec3 transmittance(1.0);
  double a = t0;
  for (int i = 1; i <= n; ++i) {
    double x = double(i) / n;
    if (distribution == StepDistribution::quadratic) x *= x;
    const double b = i == n ? t1 : t0 + (t1 - t0) * x;
    const double dt = b - a, t = 0.5 * (a + b);
    a = b;
    if (!(dt > 0.0)) continue;
    const double r_t = std::max(radius_after(r, dir.z, t), atm.bottom_radius_m);
    SkyviewRowSegment seg;
    const size_t mark = row.densities.size();
    const glm::dvec3 sigma_t =
        row_medium(atm, r_t - atm.bottom_radius_m, seg, row.densities, row.components);
    if (sigma_t == glm::dvec3(0.0)) {  // empty here: no source, no attenuation
      row.densities.resize(mark);
      continue;
    }
    const SegmentWeights w = segment_weights(sigma_t, dt);
    seg.along = (r + t * dir.z) / r_t;
    seg.across = t * sin_theta / r_t;
    seg.mu_v = clamp_cosine((t + r * dir.z) / r_t);
    seg.view_weight = transmittance * atm.sun_illuminance * w.weight;
    seg.transmittance = transmittance_at_radius(transmittance_lut, atm, r_t);
    seg.multiscattering = multiscattering_at_radius(multiscattering_lut, mapping, atm, r_t);
    row.segments.push_back(seg);
    transmittance *= w.transmittance;
  }
  return row;
}

glm::dvec3 skyview_texel_luminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                                   const Texture& transmittance_lut,
                                   const Texture& multiscattering_lut, double cos_phi,
                                   double cos_theta_s, double sin_theta_s, double nu,
                                   std::vector<glm::dvec3>& scattering_phase) {
  // sigma_s p(nu) per scattering component at density 1.
  const size_t nc = row.components.size();
  scattering_phase.resize(nc);
  for (size_t c = 0; c < nc; ++c) {
    const MediumComponent& m = *row.components[c];
    scattering_phase[c] = m.scattering_per_m * phase_function(m.phase, m.g, nu);
  }
  const double across_scale = cos_phi * sin_theta_s;
  // A view-dependent Psi_ms table: the texel's pair of nu slices, the same at every segment.
  const MultiscatteringView view =
      row.segments.empty() ? MultiscatteringView{}
                           : multiscattering_view(row.segments.front().multiscattering.mapping, nu);
  glm::dvec3 luminance(0.0);
  const double* density = row.densities.data();
  for (const SkyviewRowSegment& seg : row.segments) {
    glm::dvec3 sigma_s_phase(0.0);
    for (size_t c = 0; c < nc; ++c) sigma_s_phase += density[c] * scattering_phase[c];
    density += nc;
    const double mu_s = seg.along * cos_theta_s + seg.across * across_scale;
    const glm::dvec3 t_sun =
        lookup_sun_transmittance(transmittance_lut, seg.transmittance, atm.bottom_radius_m, mu_s);
    const glm::dvec3 source = t_sun * sigma_s_phase +
                              lookup_multiscattering(multiscattering_lut, seg.multiscattering,
                                                     mu_s, view, seg.mu_v) *
                                  seg.sigma_s;  // eq. 11
    luminance += seg.view_weight * source;
  }
  return luminance;
}

}  // namespace skybake

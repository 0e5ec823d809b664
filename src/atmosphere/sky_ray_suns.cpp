// One view ray for many suns; see the header.
#include "atmosphere/sky_ray_suns.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "core/math.hpp"

namespace skybake {

SunSharedRay::SunSharedRay(const Atmosphere& atm, const Texture& transmittance_lut,
                           const Texture* multiscattering_lut,
                           const MultiscatteringMapping* mapping, glm::dvec3 position,
                           glm::dvec3 dir, int steps)
    : atm_(atm), tlut_(transmittance_lut), mslut_(multiscattering_lut), dir_(dir) {
  if (mslut_) mapping_ = mapping ? *mapping : multiscattering_mapping_of(*mslut_);
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
  if (!span.hits_atmosphere) return;
  meets_ground_ = span.exits_on_ground;
  ground_up_ = glm::normalize(position + span.t_exit * dir);
  for (const MediumComponent& c : atm.components)
    if (c.scattering_per_m + c.absorption_per_m != glm::dvec3(0.0) && !c.density.layers.empty())
      media_.push_back(&c);  // absent ones cost nothing (the per-ray march skips them too)
  if (media_.empty()) return;
  const int n = std::max(steps, 1);
  segments_.reserve(size_t(n));
  single_.reserve(size_t(n) * media_.size());
  const double t0 = span.t_enter, t1 = span.t_exit;
  for (int i = 1; i <= n; ++i) {
    const double a = t0 + (t1 - t0) * (double(i - 1) / n);
    const double b = i == n ? t1 : t0 + (t1 - t0) * (double(i) / n);
    const double dt = b - a;
    if (!(dt > 0.0)) continue;
    const glm::dvec3 p = position + (0.5 * (a + b)) * dir;
    const double length = glm::length(p);
    const double r = std::max(length, atm.bottom_radius_m);
    const double h = r - atm.bottom_radius_m;
    glm::dvec3 sigma_s(0.0), sigma_t(0.0);
    const size_t first = single_.size();
    for (const MediumComponent* c : media_) {
      const double d = density_at(c->density, h);
      single_.push_back(d * c->scattering_per_m);
      sigma_s += d * c->scattering_per_m;
      sigma_t += d * (c->scattering_per_m + c->absorption_per_m);
    }
    if (sigma_t == glm::dvec3(0.0)) {  // empty here: no source, no attenuation
      single_.resize(first);
      continue;
    }
    const SegmentWeights w = segment_weights(sigma_t, dt);
    const glm::dvec3 k = transmittance_ * atm.sun_illuminance * w.weight;
    for (size_t j = first; j < single_.size(); ++j) single_[j] *= k;
    Segment s;
    s.up = p / length;
    s.mu_v = glm::dot(p, dir) / r;
    s.sun_read = transmittance_at_radius(transmittance_lut, atm, std::min(r, atm.top_radius_m));
    if (mslut_) s.psi_read = multiscattering_at_radius(*mslut_, mapping_, atm, r);
    s.ms = k * sigma_s;
    segments_.push_back(s);
    transmittance_ *= w.transmittance;
  }
}

glm::dvec3 SunSharedRay::scattered(glm::dvec3 sun_dir) const {
  const double nu = clamp_cosine(glm::dot(dir_, sun_dir));
  thread_local std::vector<double> phase;  // kept from call to call: no allocation per sun
  const size_t m = media_.size();
  phase.resize(m);
  for (size_t k = 0; k < m; ++k) phase[k] = phase_function(media_[k]->phase, media_[k]->g, nu);
  const MultiscatteringView view = mslut_ ? multiscattering_view(mapping_, nu) : MultiscatteringView{};
  glm::dvec3 l(0.0);
  const glm::dvec3* single = single_.data();
  for (const Segment& s : segments_) {
    const double mu_s = clamp_cosine(glm::dot(s.up, sun_dir));
    glm::dvec3 source(0.0);
    for (size_t k = 0; k < m; ++k) source += single[k] * phase[k];
    single += m;
    l += lookup_sun_transmittance(tlut_, s.sun_read, atm_.bottom_radius_m, mu_s) * source;
    if (mslut_) l += lookup_multiscattering(*mslut_, s.psi_read, mu_s, view, s.mu_v) * s.ms;
  }
  return l;
}

glm::dvec3 SunSharedRay::sunlit_ground(glm::dvec3 sun_dir) const {
  if (!meets_ground_) return glm::dvec3(0.0);
  const double mu_s = clamp_cosine(glm::dot(ground_up_, sun_dir));
  if (mu_s <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 t_sun = lookup_sun_transmittance(tlut_, atm_, atm_.bottom_radius_m, mu_s);
  return transmittance_ * atm_.sun_illuminance * t_sun * mu_s * atm_.ground_albedo / kPi;
}

}  // namespace skybake

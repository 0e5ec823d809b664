#include "atmosphere/hillaire_demo_march.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/phase.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/math.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

double demo_sphere_nearest(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 centre, double radius) {
  const glm::dvec3 oc = origin - centre;
  const double b = 2.0 * glm::dot(dir, oc);
  const double c = glm::dot(oc, oc) - radius * radius;
  const double delta = b * b - 4.0 * c;
  if (delta < 0.0) return -1.0;
  const double s0 = 0.5 * (-b - std::sqrt(delta)), s1 = 0.5 * (-b + std::sqrt(delta));
  if (s0 < 0.0 && s1 < 0.0) return -1.0;
  if (s0 < 0.0) return std::max(0.0, s1);
  if (s1 < 0.0) return std::max(0.0, s0);
  return std::max(0.0, std::min(s0, s1));
}

double demo_to_sub_uv(double x, double n) { return (x + 0.5 / n) * (n / (n + 1.0)); }
double demo_from_sub_uv(double u, double n) { return (u - 0.5 / n) * (n / (n - 1.0)); }

namespace {

glm::dvec3 demo_march_rgb(const Texture& t, double u, double v, int layer = 0) {
  return glm::dvec3(sample_bilinear(t, u, v, 0, layer, false));
}

// sigma_s times the phase at scattering cosine nu, summed over components
// (his MieRayPhase), or times the isotropic phase.
glm::dvec3 demo_phase_scattering(const Atmosphere& atm, double altitude, double nu, bool real_phase) {
  glm::dvec3 sum(0.0);
  for (const MediumComponent& c : atm.components) {
    const double p = real_phase ? phase_function(c.phase, c.g, nu) : isotropic_phase();
    sum += density_at(c.density, altitude) * c.scattering_per_m * p;
  }
  return sum;
}

// His MoveToTopAtmosphere: false when the ray misses the atmosphere.
bool demo_move_to_top(const Atmosphere& atm, glm::dvec3& position, glm::dvec3 dir) {
  const double r = glm::length(position);
  if (r <= atm.top_radius_m) return true;
  const double t = demo_sphere_nearest(position, dir, glm::dvec3(0.0), atm.top_radius_m);
  if (t < 0.0) return false;
  // PLANET_RADIUS_OFFSET: a viewer moved to the top is put that far inside
  // (and the planet's-shadow sphere below is raised by it).
  position = position + dir * t - position / r * kDemoGroundOffsetM;
  return true;
}

// Where the march ends: the ground or the top, 0 when it misses both.
double demo_march_end(const Atmosphere& atm, glm::dvec3 position, glm::dvec3 dir, bool& on_ground) {
  const double t_bottom = demo_sphere_nearest(position, dir, glm::dvec3(0.0), atm.bottom_radius_m);
  const double t_top = demo_sphere_nearest(position, dir, glm::dvec3(0.0), atm.top_radius_m);
  on_ground = false;
  if (t_bottom < 0.0) return t_top < 0.0 ? 0.0 : t_top;
  if (t_top > 0.0) {
    on_ground = t_bottom <= t_top && t_bottom > 0.0;
    return std::min(t_top, t_bottom);
  }
  return 0.0;
}

}  // namespace

glm::dvec3 demo_read_transmittance(const Atmosphere& atm, const Texture& lut, double r,
                                   double mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double h = std::sqrt(std::max(0.0, rt * rt - rb * rb));
  const double rho = std::sqrt(std::max(0.0, r * r - rb * rb));
  const double disc = r * r * (mu * mu - 1.0) + rt * rt;
  const double d = std::max(0.0, -r * mu + std::sqrt(std::max(disc, 0.0)));
  const double d_min = rt - r, d_max = rho + h;
  return demo_march_rgb(lut, (d - d_min) / (d_max - d_min), rho / h);
}

glm::dvec3 demo_read_multiscattering(const Atmosphere& atm, const Texture& lut, double r,
                                     double mu_s) {
  const double n = lut.width;
  const double x = std::clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
  const double y =
      std::clamp((r - atm.bottom_radius_m) / (atm.top_radius_m - atm.bottom_radius_m), 0.0, 1.0);
  return demo_march_rgb(lut, demo_to_sub_uv(x, n), demo_to_sub_uv(y, n));
}

DemoMarchResult demo_integrate(const Atmosphere& atm, const DemoTables& tables,
                               glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir,
                               const DemoMarch& march) {
  DemoMarchResult out;
  if (!demo_move_to_top(atm, position, dir)) return out;
  bool on_ground = false;
  double t_max = demo_march_end(atm, position, dir, on_ground);
  if (t_max > march.max_distance) {
    t_max = march.max_distance;
    on_ground = false;
  }
  if (!(t_max > 0.0)) return out;
  double count = march.min_samples, count_floor = count, t_max_floor = t_max;
  if (march.variable) {
    // His lerp over saturate(tMax * 0.01) with tMax in km.
    count = march.min_samples +
            (march.max_samples - march.min_samples) * std::clamp(t_max * 1e-5, 0.0, 1.0);
    count_floor = std::floor(count);
    t_max_floor = t_max * count_floor / count;
  }
  const double nu = glm::dot(sun_dir, dir);
  glm::dvec3 throughput(1.0);
  double t = 0.0, dt = t_max / count;
  for (double s = 0.0; s < count; s += 1.0) {
    if (march.variable) {
      const double a = s / count_floor, b = (s + 1.0) / count_floor;
      const double t0 = t_max_floor * a * a;
      const double t1 = b * b > 1.0 ? t_max : t_max_floor * b * b;
      t = t0 + (t1 - t0) * march.segment_t;
      dt = t1 - t0;
    } else {
      const double next = t_max * (s + march.segment_t) / count;
      dt = next - t;
      t = next;
    }
    const glm::dvec3 p = position + t * dir;
    const double r = glm::length(p);
    const glm::dvec3 up = p / r;
    const MediumSample m = sample_medium(atm, r - atm.bottom_radius_m);
    const glm::dvec3 step_t = glm::exp(-m.extinction * dt);
    out.optical_depth += m.extinction * dt;
    const double mu_s = glm::dot(sun_dir, up);
    const glm::dvec3 sun_t =
        tables.transmittance ? demo_read_transmittance(atm, *tables.transmittance, r, mu_s)
                             : glm::dvec3(0.0);
    const double shadow =
        demo_sphere_nearest(p, sun_dir, kDemoGroundOffsetM * up, atm.bottom_radius_m) >= 0.0 ? 0.0 : 1.0;
    const glm::dvec3 psi = tables.multiscattering
                               ? demo_read_multiscattering(atm, *tables.multiscattering, r, mu_s)
                               : glm::dvec3(0.0);
    const glm::dvec3 source =
        shadow * sun_t * demo_phase_scattering(atm, r - atm.bottom_radius_m, nu, march.mie_ray_phase) +
        psi * m.scattering;
    const glm::dvec3 safe_ext = glm::max(m.extinction, glm::dvec3(1e-30));
    out.multi_scat_as_1 += throughput * (m.scattering - m.scattering * step_t) / safe_ext;
    out.luminance += throughput * (source - source * step_t) / safe_ext;
    throughput *= step_t;
  }
  if (march.lit_ground && on_ground && tables.transmittance) {
    const glm::dvec3 p = position + t_max * dir;
    const double r = glm::length(p);
    const double mu_s = glm::dot(sun_dir, p / r);
    out.luminance += demo_read_transmittance(atm, *tables.transmittance, r, mu_s) * throughput *
                     std::clamp(mu_s, 0.0, 1.0) * atm.ground_albedo / kPi;
  }
  out.transmittance = throughput;
  return out;
}

}  // namespace skybake

#include "report/hillaire_march.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "atmosphere/phase.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/math.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

namespace {

// His PLANET_RADIUS_OFFSET (0.01 km): the planet's-shadow sphere is raised
// by it, and a viewer moved to the top is put that far inside.
constexpr double kOffsetM = 10.0;
// Nearest non-negative distance to a sphere, -1 when there is none (his
// raySphereIntersectNearest).
double sphere_nearest(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 centre, double radius) {
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

// fromUnitToSubUvs and fromSubUvsToUnit.
double to_sub_uv(double x, double n) { return (x + 0.5 / n) * (n / (n + 1.0)); }
double from_sub_uv(double u, double n) { return (u - 0.5 / n) * (n / (n - 1.0)); }

glm::dvec3 sample_rgb(const Texture& t, double u, double v, int layer = 0) {
  return glm::dvec3(sample_bilinear(t, u, v, 0, layer, false));
}

// sigma_s times the phase at scattering cosine nu, summed over components
// (his MieRayPhase), or times the isotropic phase.
glm::dvec3 phase_scattering(const Atmosphere& atm, double altitude, double nu, bool real_phase) {
  glm::dvec3 sum(0.0);
  for (const MediumComponent& c : atm.components) {
    const double p = real_phase ? phase_function(c.phase, c.g, nu) : isotropic_phase();
    sum += density_at(c.density, altitude) * c.scattering_per_m * p;
  }
  return sum;
}

// His MoveToTopAtmosphere: false when the ray misses the atmosphere.
bool move_to_top(const Atmosphere& atm, glm::dvec3& position, glm::dvec3 dir) {
  const double r = glm::length(position);
  if (r <= atm.top_radius_m) return true;
  const double t = sphere_nearest(position, dir, glm::dvec3(0.0), atm.top_radius_m);
  if (t < 0.0) return false;
  position = position + dir * t - position / r * kOffsetM;
  return true;
}

// Where the march ends: the ground or the top, 0 when it misses both.
double march_end(const Atmosphere& atm, glm::dvec3 position, glm::dvec3 dir, bool& on_ground) {
  const double t_bottom = sphere_nearest(position, dir, glm::dvec3(0.0), atm.bottom_radius_m);
  const double t_top = sphere_nearest(position, dir, glm::dvec3(0.0), atm.top_radius_m);
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
  return sample_rgb(lut, (d - d_min) / (d_max - d_min), rho / h);
}

glm::dvec3 demo_read_multiscattering(const Atmosphere& atm, const Texture& lut, double r,
                                     double mu_s) {
  const double n = lut.width;
  const double x = std::clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
  const double y =
      std::clamp((r - atm.bottom_radius_m) / (atm.top_radius_m - atm.bottom_radius_m), 0.0, 1.0);
  return sample_rgb(lut, to_sub_uv(x, n), to_sub_uv(y, n));
}

DemoMarchResult demo_integrate(const Atmosphere& atm, const DemoTables& tables,
                               glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir,
                               const DemoMarch& march) {
  DemoMarchResult out;
  if (!move_to_top(atm, position, dir)) return out;
  bool on_ground = false;
  const double t_max = march_end(atm, position, dir, on_ground);
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
        sphere_nearest(p, sun_dir, kOffsetM * up, atm.bottom_radius_m) >= 0.0 ? 0.0 : 1.0;
    const glm::dvec3 psi = tables.multiscattering
                               ? demo_read_multiscattering(atm, *tables.multiscattering, r, mu_s)
                               : glm::dvec3(0.0);
    const glm::dvec3 source =
        shadow * sun_t * phase_scattering(atm, r - atm.bottom_radius_m, nu, march.mie_ray_phase) +
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

glm::dvec3 demo_read_skyview(const Atmosphere& atm, const Texture& lut, int layer,
                             glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir) {
  const double r = glm::length(position);
  const glm::dvec3 up = position / r;
  const double cos_zenith = glm::dot(dir, up);
  const glm::dvec3 side = glm::normalize(glm::cross(up, dir));
  const glm::dvec3 forward = glm::normalize(glm::cross(side, up));
  const glm::dvec2 light = glm::normalize(glm::dvec2(glm::dot(sun_dir, forward),
                                                     glm::dot(sun_dir, side)));
  const bool ground = sphere_nearest(position, dir, glm::dvec3(0.0), atm.bottom_radius_m) >= 0.0;
  const double rb = atm.bottom_radius_m;
  const double beta = std::acos(std::sqrt(std::max(0.0, r * r - rb * rb)) / r);
  const double zenith_horizon = kPi - beta;
  const double theta = std::acos(clamp_cosine(cos_zenith));
  const double y = ground ? 0.5 * std::sqrt(std::max(0.0, (theta - zenith_horizon) / beta)) + 0.5
                          : 0.5 * (1.0 - std::sqrt(std::max(0.0, 1.0 - theta / zenith_horizon)));
  const double x = std::sqrt(std::max(0.0, -light.x * 0.5 + 0.5));
  return sample_rgb(lut, to_sub_uv(x, kDemoSkyviewWidth), to_sub_uv(y, kDemoSkyviewHeight), layer);
}

Texture demo_transmittance_pass(const Atmosphere& atm, int width, int height) {
  Texture tex(width, height, 1, 1, {"R", "G", "B"});
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double h = std::sqrt(rt * rt - rb * rb);
  DemoMarch march;
  march.variable = false;
  march.min_samples = 40.0;
  march.mie_ray_phase = false;
  tbb::parallel_for(0, height, [&](int j) {
    for (int i = 0; i < width; ++i) {
      // UvToLutTransmittanceParams at the pixel centre, no sub-uv remap.
      const double x_mu = texel_center(i, width), rho = h * texel_center(j, height);
      const double r = std::sqrt(rho * rho + rb * rb);
      const double d_min = rt - r, d_max = rho + h, d = d_min + x_mu * (d_max - d_min);
      const double mu = d == 0.0 ? 1.0 : clamp_cosine((h * h - rho * rho - d * d) / (2.0 * r * d));
      const glm::dvec3 dir(0.0, std::sqrt(std::max(0.0, 1.0 - mu * mu)), mu);
      const DemoMarchResult res =
          demo_integrate(atm, {}, {0.0, 0.0, r}, dir, {0.0, 0.0, 1.0}, march);
      const glm::dvec3 t = glm::exp(-res.optical_depth);
      for (int c = 0; c < 3; ++c) tex.at(i, j, 0, 0, c) = float(t[c]);
    }
  });
  return tex;
}

Texture demo_multiscattering_pass(const Atmosphere& atm, const Texture& transmittance, int size) {
  Texture tex(size, size, 1, 1, {"R", "G", "B"});
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  DemoMarch march;
  march.variable = false;
  march.min_samples = 20.0;
  march.mie_ray_phase = false;
  march.lit_ground = true;
  const DemoTables tables{&transmittance, nullptr};
  tbb::parallel_for(0, size, [&](int j) {
    for (int i = 0; i < size; ++i) {
      const double x = from_sub_uv(texel_center(i, size), size);
      const double y = from_sub_uv(texel_center(j, size), size);
      const double mu_s = x * 2.0 - 1.0;
      const glm::dvec3 sun(0.0, std::sqrt(std::clamp(1.0 - mu_s * mu_s, 0.0, 1.0)), mu_s);
      // His altitude: the unit value raised by PLANET_RADIUS_OFFSET (a length
      // in km added to a unit value: 1 % of the shell).
      const double r = rb + std::clamp(y + 0.01, 0.0, 1.0) * (rt - rb - kOffsetM);
      glm::dvec3 l2(0.0), f_ms(0.0);
      for (int k = 0; k < 64; ++k) {
        const double theta = 2.0 * kPi * (0.5 + k / 8) / 8.0;
        const double phi = std::acos(1.0 - 2.0 * (0.5 + k % 8) / 8.0);
        const glm::dvec3 dir(std::cos(theta) * std::sin(phi), std::sin(theta) * std::sin(phi),
                             std::cos(phi));
        const DemoMarchResult res = demo_integrate(atm, tables, {0.0, 0.0, r}, dir, sun, march);
        l2 += res.luminance / 64.0;
        f_ms += res.multi_scat_as_1 / 64.0;
      }
      const glm::dvec3 psi = l2 / (1.0 - f_ms);
      for (int c = 0; c < 3; ++c) tex.at(i, j, 0, 0, c) = float(psi[c]);
    }
  });
  return tex;
}

Texture demo_skyview_pass(const Atmosphere& atm, const DemoTables& tables, double altitude_m,
                          glm::dvec3 sun_dir, const DemoMarch& march) {
  const int w = kDemoSkyviewWidth, hgt = kDemoSkyviewHeight;
  Texture tex(w, hgt, 1, 1, {"R", "G", "B"});
  const double rb = atm.bottom_radius_m, r = rb + altitude_m;
  const double beta = std::acos(std::sqrt(std::max(0.0, r * r - rb * rb)) / r);
  const double zenith_horizon = kPi - beta;
  const double cs = clamp_cosine(sun_dir.z);
  const glm::dvec3 sun(std::sqrt(1.0 - cs * cs), 0.0, cs);
  tbb::parallel_for(0, hgt, [&](int j) {
    const double y = from_sub_uv(texel_center(j, hgt), hgt);
    double cos_zenith;
    if (y < 0.5) {
      const double c = 1.0 - 2.0 * y;
      cos_zenith = std::cos(zenith_horizon * (1.0 - c * c));
    } else {
      const double c = 2.0 * y - 1.0;
      cos_zenith = std::cos(zenith_horizon + beta * c * c);
    }
    const double sin_zenith = std::sqrt(std::max(0.0, 1.0 - cos_zenith * cos_zenith));
    for (int i = 0; i < w; ++i) {
      const double x = from_sub_uv(texel_center(i, w), w);
      const double light_view = -(x * x * 2.0 - 1.0);
      const glm::dvec3 dir(sin_zenith * light_view,
                           sin_zenith * std::sqrt(std::max(0.0, 1.0 - light_view * light_view)),
                           cos_zenith);
      const glm::dvec3 l = demo_integrate(atm, tables, {0.0, 0.0, r}, dir, sun, march).luminance;
      for (int c = 0; c < 3; ++c) tex.at(i, j, 0, 0, c) = float(l[c]);
    }
  });
  return tex;
}

}  // namespace skybake

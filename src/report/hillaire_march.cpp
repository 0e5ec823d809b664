#include "report/hillaire_march.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "atmosphere/table_convention.hpp"
#include "core/math.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

namespace {

// His PLANET_RADIUS_OFFSET (0.01 km), in the multiscattering pass's altitude.
constexpr double kPassOffsetM = 10.0;

glm::dvec3 hillaire_pass_rgb(const Texture& t, double u, double v, int layer = 0) {
  return glm::dvec3(sample_bilinear(t, u, v, 0, layer, false));
}

}  // namespace

glm::dvec3 demo_read_skyview(const Atmosphere& atm, const Texture& lut, int layer,
                             glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir) {
  const double r = glm::length(position);
  const glm::dvec3 up = position / r;
  const double cos_zenith = glm::dot(dir, up);
  const glm::dvec3 side = glm::normalize(glm::cross(up, dir));
  const glm::dvec3 forward = glm::normalize(glm::cross(side, up));
  const glm::dvec2 light = glm::normalize(glm::dvec2(glm::dot(sun_dir, forward),
                                                     glm::dot(sun_dir, side)));
  const bool ground = demo_sphere_nearest(position, dir, glm::dvec3(0.0), atm.bottom_radius_m) >= 0.0;
  const double rb = atm.bottom_radius_m;
  const double beta = std::acos(std::sqrt(std::max(0.0, r * r - rb * rb)) / r);
  const double zenith_horizon = kPi - beta;
  const double theta = std::acos(clamp_cosine(cos_zenith));
  const double y = ground ? 0.5 * std::sqrt(std::max(0.0, (theta - zenith_horizon) / beta)) + 0.5
                          : 0.5 * (1.0 - std::sqrt(std::max(0.0, 1.0 - theta / zenith_horizon)));
  const double x = std::sqrt(std::max(0.0, -light.x * 0.5 + 0.5));
  return hillaire_pass_rgb(lut, demo_to_sub_uv(x, kDemoSkyviewWidth),
                           demo_to_sub_uv(y, kDemoSkyviewHeight), layer);
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
      const double x = demo_from_sub_uv(texel_center(i, size), size);
      const double y = demo_from_sub_uv(texel_center(j, size), size);
      const double mu_s = x * 2.0 - 1.0;
      const glm::dvec3 sun(0.0, std::sqrt(std::clamp(1.0 - mu_s * mu_s, 0.0, 1.0)), mu_s);
      // His altitude: the unit value raised by PLANET_RADIUS_OFFSET (a length
      // in km added to a unit value: 1 % of the shell).
      const double r = rb + std::clamp(y + 0.01, 0.0, 1.0) * (rt - rb - kPassOffsetM);
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
    const double y = demo_from_sub_uv(texel_center(j, hgt), hgt);
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
      const double x = demo_from_sub_uv(texel_center(i, w), w);
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

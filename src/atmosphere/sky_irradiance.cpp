#include "atmosphere/sky_irradiance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_ray_suns.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/skyview_multiple4d.hpp"
#include "atmosphere/sphere_rule.hpp"

namespace skybake {

namespace {

double height_of(const Atmosphere& atm) { return atm.top_radius_m - atm.bottom_radius_m; }

// Read of ground_sky_irradiance's table at a sun cosine: geometric between
// nodes where both are lit, as the light falls about 2x per degree of sun
// in twilight and a linear read overshoots (Earth's sky 4 degrees into
// twilight 4.8 -> 3.4% RMS); linear where a node is 0.
glm::dvec3 ground_sky_at(const std::vector<glm::dvec3>& table, double mu_s) {
  const int n = int(table.size());
  const double x = std::clamp(0.5 * (mu_s + 1.0), 0.0, 1.0) * (n - 1);
  const int i = std::min(int(x), n - 2);
  const double f = x - i;
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    const double a = table[i][c], b = table[i + 1][c];
    out[c] = a > 0.0 && b > 0.0 ? a * std::pow(b / a, f) : a * (1.0 - f) + b * f;
  }
  return out;
}

// A ray of `source`, marched once for any number of suns (sky_ray_suns.hpp):
// the field source's march is single scattering only, the psi_ms source's
// reads its table.
SunSharedRay source_ray(const Atmosphere& atm, const SkyRadianceSource& source,
                        glm::dvec3 position, glm::dvec3 dir, int steps) {
  return SunSharedRay(atm, *source.transmittance, source.field ? nullptr : source.multiscattering,
                      &source.mapping, position, dir, steps);
}

// That ray's radiance for one sun.
// - field: single scattering marched, orders >= 2 from the 4D field, and
//   where the ray meets the ground, the ground lit by every order;
// - psi_ms: the march with Psi_ms, the ground lit by the sun and, with a
//   ground_sky table, by the sky.
glm::dvec3 source_ray_radiance(const Atmosphere& atm, const SkyRadianceSource& source,
                               const SunSharedRay& ray, bool sky_only, glm::dvec3 position,
                               glm::dvec3 dir, glm::dvec3 sun_dir, double sun_zenith_rad) {
  glm::dvec3 l = ray.scattered(sun_dir);
  const double r = glm::length(position);
  if (source.field)
    l += lookup_field_multiple_scattering(
        atm, *source.field, r, skyview_direction_from_vectors(position / r, dir, sun_dir),
        sun_zenith_rad);
  if (sky_only || !ray.meets_ground()) return l;
  const double mu_s = glm::dot(ray.ground_up(), sun_dir);
  const glm::dvec3 through = ray.transmittance() * atm.ground_albedo / kPi;
  if (source.field)
    return l + through * lookup_irradiance(source.field->ground_irradiance, atm,
                                           atm.bottom_radius_m, mu_s);
  l += ray.sunlit_ground(sun_dir);
  return source.ground_sky.empty() ? l : l + through * ground_sky_at(source.ground_sky, mu_s);
}

glm::dvec3 sun_in_plane(double sun_zenith_rad) {
  return {std::sin(sun_zenith_rad), 0.0, std::cos(sun_zenith_rad)};
}

}  // namespace

const SkyRadianceSource& source_for_sun(const SkyRadianceSource& source, double sun_zenith_rad) {
  return source.below_horizon && sun_below_horizon(sun_zenith_rad) ? *source.below_horizon
                                                                    : source;
}

std::string radiance_source_name(const SkyRadianceSource& source) {
  return source.field ? "field" : "psi_ms";
}

void set_sky_light_source_metadata(Metadata& m, const SkyRadianceSource& source) {
  set_meta(m, "radiance_source", radiance_source_name(source));
  if (source.field) set_meta(m, "energy_out_over_in", source.field->energy_out_over_in);
  if (!source.below_horizon) return;
  const SkyRadianceSource& b = *source.below_horizon;
  set_meta(m, "radiance_source_below_horizon", radiance_source_name(b));
  if (!b.field) return;
  const ScatteringShape& t = b.field->shape;
  set_meta(m, "below_horizon_field_shape", fmt::format("{}x{}x{}x{}", t.r_size, t.mu_size,
                                                       t.mu_s_size, t.nu_size));
  set_meta(m, "below_horizon_mu_s_min", t.mu_s_min);
}

glm::dvec3 sky_source_radiance(const Atmosphere& atm, const SkyRadianceSource& source,
                               bool sky_only, int steps, glm::dvec3 position, glm::dvec3 dir,
                               glm::dvec3 sun_dir) {
  const double mu_s = glm::dot(glm::normalize(position), sun_dir);
  const double sun_zenith = std::acos(std::clamp(mu_s, -1.0, 1.0));
  const SkyRadianceSource& src = source_for_sun(source, sun_zenith);
  const SunSharedRay ray = source_ray(atm, src, position, dir, steps);
  return source_ray_radiance(atm, src, ray, sky_only, position, dir, sun_dir, sun_zenith);
}

double sky_irradiance_sun_zenith(const SkyIrradianceSpec& spec, int x) {
  return spec.width > 1 ? spec.max_sun_zenith_rad * x / (spec.width - 1) : 0.0;
}

double sky_irradiance_altitude(const Atmosphere& atm, const SkyIrradianceSpec& spec, int y) {
  const double v = spec.height > 1 ? double(y) / (spec.height - 1) : 0.0;
  return height_of(atm) * v * v;
}

std::vector<glm::dvec3> ground_sky_irradiance(const Atmosphere& atm,
                                              const Texture& transmittance_lut,
                                              const Texture& multiscattering_lut,
                                              const SkyIrradianceSpec& spec, int nodes) {
  // Upward rays from the ground see only sky: one node below the split, never cast.
  const SphereRule rule = symmetric_gauss_rule(1, spec.above, spec.azimuths, 0.0);
  const MultiscatteringMapping mapping = multiscattering_mapping_of(multiscattering_lut);
  const glm::dvec3 position(0.0, 0.0, atm.bottom_radius_m);
  std::vector<size_t> upward;
  for (size_t k = 0; k < rule.dirs.size(); ++k)
    if (rule.dirs[k].z > 0.0) upward.push_back(k);
  // Each ray marched once for every node's sun; the terms kept per (node,
  // ray) and summed in the rule's order, whatever the threads.
  const size_t m = upward.size();
  std::vector<glm::dvec3> terms(m * size_t(nodes));
  tbb::parallel_for(size_t(0), m, [&](size_t u) {
    const glm::dvec3 d = rule.dirs[upward[u]];
    const SunSharedRay ray(atm, transmittance_lut, &multiscattering_lut, &mapping, position, d,
                           spec.steps);
    for (int i = 0; i < nodes; ++i) {
      const double mu_s = -1.0 + 2.0 * i / (nodes - 1);
      const glm::dvec3 sun(std::sqrt(std::max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);
      terms[size_t(i) * m + u] = rule.weights[upward[u]] * d.z * ray.scattered(sun);
    }
  });
  std::vector<glm::dvec3> table(nodes, glm::dvec3(0.0));
  for (int i = 0; i < nodes; ++i) {
    glm::dvec3 e(0.0);
    for (size_t u = 0; u < m; ++u) e += terms[size_t(i) * m + u];
    table[i] = 4.0 * kPi * e;
  }
  return table;
}

SkyRadianceSource psi_ms_source(const Atmosphere& atm, const Texture& transmittance_lut,
                                const Texture& multiscattering_lut, const SkyIrradianceSpec& spec) {
  SkyRadianceSource source;
  source.transmittance = &transmittance_lut;
  source.multiscattering = &multiscattering_lut;
  source.mapping = multiscattering_mapping_of(multiscattering_lut);
  if (!spec.sky_only)
    source.ground_sky = ground_sky_irradiance(atm, transmittance_lut, multiscattering_lut, spec,
                                              kGroundSkyNodes);
  return source;
}

std::vector<ShRadiance> compute_sky_radiance_sh_suns(const Atmosphere& atm,
                                                     const SkyRadianceSource& sources,
                                                     const SkyIrradianceSpec& spec,
                                                     double altitude_m,
                                                     const std::vector<double>& sun_zeniths_rad) {
  const double r = atm.bottom_radius_m + std::clamp(altitude_m, 0.0, height_of(atm));
  const SphereRule rule = symmetric_gauss_rule(spec.below, spec.above, spec.azimuths,
                                               horizon_zenith_cosine(atm.bottom_radius_m, r));
  const glm::dvec3 position(0.0, 0.0, r);
  std::vector<ShRadiance> out(sun_zeniths_rad.size());
  for (ShRadiance& sh : out) sh.fill(glm::dvec3(0.0));
  std::vector<glm::dvec3> suns_dir(sun_zeniths_rad.size());
  for (size_t j = 0; j < suns_dir.size(); ++j) suns_dir[j] = sun_in_plane(sun_zeniths_rad[j]);
  for (const SkyRadianceSource* source : {&sources, sources.below_horizon}) {
    if (!source) continue;
    std::vector<size_t> suns;  // the columns that read this source
    for (size_t j = 0; j < sun_zeniths_rad.size(); ++j)
      if (&source_for_sun(sources, sun_zeniths_rad[j]) == source) suns.push_back(j);
    if (suns.empty()) continue;
    for (size_t k = 0; k < rule.dirs.size(); ++k) {
      const glm::dvec3 d = rule.dirs[k];
      const SunSharedRay ray = source_ray(atm, *source, position, d, spec.steps);
      const std::array<double, kShL2Count> y = sh_l2_basis(d);
      for (size_t j : suns) {
        const glm::dvec3 l = source_ray_radiance(atm, *source, ray, spec.sky_only, position, d,
                                                 suns_dir[j], sun_zeniths_rad[j]);
        // The rule stands each ray for itself and its mirror image in y: the
        // y-odd functions cancel in pairs, so only the others are summed.
        for (int i : kShSymmetricIndex) out[j][i] += rule.weights[k] * y[i] * l;
      }
    }
  }
  for (ShRadiance& sh : out)
    for (glm::dvec3& c : sh) c *= 4.0 * kPi;  // the weights are fractions of 4 pi
  return out;
}

ShRadiance compute_sky_radiance_sh(const Atmosphere& atm, const SkyRadianceSource& sources,
                                   const SkyIrradianceSpec& spec, double altitude_m,
                                   double sun_zenith_rad) {
  return compute_sky_radiance_sh_suns(atm, sources, spec, altitude_m, {sun_zenith_rad}).front();
}

Texture bake_sky_irradiance(const Atmosphere& atm, const SkyRadianceSource& source,
                            const SkyIrradianceSpec& spec, const BakeContext& ctx) {
  Texture tex(spec.width, spec.height, 1, kShSymmetricCount, {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(spec.height));
  std::vector<double> zeniths(spec.width);
  for (int x = 0; x < spec.width; ++x) zeniths[x] = sky_irradiance_sun_zenith(spec, x);
  // A row's columns share its rays (sky_ray_suns.hpp).
  tbb::parallel_for(0, spec.height, [&](int y) {
    const std::vector<ShRadiance> row = compute_sky_radiance_sh_suns(
        atm, source, spec, sky_irradiance_altitude(atm, spec, y), zeniths);
    for (int x = 0; x < spec.width; ++x) {
      const std::array<glm::dvec3, kShSymmetricCount> stored = encode_sky_radiance_sh(row[x]);
      for (int j = 0; j < kShSymmetricCount; ++j)
        for (int c = 0; c < 3; ++c) tex.at(x, y, 0, j, c) = float(stored[j][c]);
    }
    progress.tick();
  });
  Metadata& m = tex.metadata;
  set_meta(m, "parameterization", std::string("sky_irradiance_sh_l2"));
  set_sky_light_source_metadata(m, source);
  set_meta(m, "sh_layers",
           std::string("ln(L00), L10/L00, L11/L00, L20/L00, L21/L00, L22/L00"));
  set_meta(m, "sh_frame",
           std::string("z up, sun at azimuth 0 in the x-z plane; y-odd coefficients are 0"));
  set_meta(m, "sh_normalization", std::string("orthonormal real SH (Ramamoorthi-Hanrahan 2001)"));
  set_meta(m, "max_sun_zenith_deg", spec.max_sun_zenith_rad / kDeg);
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  set_meta(m, "atmosphere_height_m", height_of(atm));
  set_meta(m, "altitude_mapping", std::string("quadratic"));
  set_meta(m, "sky_only", spec.sky_only ? 1 : 0);
  set_meta(m, "direction_rule",
           fmt::format("Gauss-Legendre zenith cosines, {} below and {} above the horizon, x {} "
                       "midpoint azimuths on (0, pi) weighted twice",
                       spec.below, spec.above, spec.azimuths));
  set_meta(m, "steps", spec.steps);
  return tex;
}

ShRadiance lookup_sky_radiance_sh(const Texture& table, double altitude_m, double sun_zenith_rad) {
  const double max_zenith = meta_double(table.metadata, "max_sun_zenith_deg") * kDeg;
  const double height = meta_double(table.metadata, "atmosphere_height_m");
  const double u = std::clamp(sun_zenith_rad / max_zenith, 0.0, 1.0);
  const double v = std::sqrt(std::clamp(altitude_m / height, 0.0, 1.0));
  const double fx = u * (table.width - 1), fy = v * (table.height - 1);
  const int x0 = std::min(int(fx), std::max(table.width - 2, 0));
  const int y0 = std::min(int(fy), std::max(table.height - 2, 0));
  const int x1 = std::min(x0 + 1, table.width - 1), y1 = std::min(y0 + 1, table.height - 1);
  const double ax = fx - x0, ay = fy - y0;
  std::array<glm::dvec3, kShSymmetricCount> stored;
  for (int j = 0; j < kShSymmetricCount; ++j) {
    for (int ch = 0; ch < 3; ++ch) {
      const double a = table.at(x0, y0, 0, j, ch) * (1 - ax) + table.at(x1, y0, 0, j, ch) * ax;
      const double b = table.at(x0, y1, 0, j, ch) * (1 - ax) + table.at(x1, y1, 0, j, ch) * ax;
      stored[j][ch] = a * (1 - ay) + b * ay;
    }
  }
  return decode_sky_radiance_sh(stored);
}

std::array<glm::dvec3, kShSymmetricCount> encode_sky_radiance_sh(const ShRadiance& sh) {
  std::array<glm::dvec3, kShSymmetricCount> stored;
  const glm::dvec3 l00 = glm::max(sh[0], glm::dvec3(kMinStoredL00));
  stored[0] = glm::log(l00);
  for (int j = 1; j < kShSymmetricCount; ++j) stored[j] = sh[kShSymmetricIndex[j]] / l00;
  return stored;
}

ShRadiance decode_sky_radiance_sh(const std::array<glm::dvec3, kShSymmetricCount>& stored) {
  ShRadiance sh;
  sh.fill(glm::dvec3(0.0));
  const glm::dvec3 l00 = glm::exp(stored[0]);
  sh[0] = l00;
  for (int j = 1; j < kShSymmetricCount; ++j) sh[kShSymmetricIndex[j]] = stored[j] * l00;
  return sh;
}

SkyFrame sky_frame(glm::dvec3 up, glm::dvec3 sun_dir) {
  SkyFrame f;
  f.z = up;
  const double mu_s = std::clamp(glm::dot(up, sun_dir), -1.0, 1.0);
  glm::dvec3 x = sun_dir - mu_s * up;
  if (glm::dot(x, x) < 1e-24) {
    // Sun at the zenith or nadir: the sky is symmetric about z, any x will do.
    x = std::abs(up.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    x -= glm::dot(x, up) * up;
  }
  f.x = glm::normalize(x);
  f.y = glm::cross(f.z, f.x);
  f.sun_zenith_rad = std::acos(mu_s);
  return f;
}

glm::dvec3 lookup_sky_irradiance(const Texture& table, glm::dvec3 n, glm::dvec3 up,
                                 glm::dvec3 sun_dir, double altitude_m) {
  const SkyFrame f = sky_frame(up, sun_dir);
  const glm::dvec3 local(glm::dot(n, f.x), glm::dot(n, f.y), glm::dot(n, f.z));
  return sh_l2_irradiance(lookup_sky_radiance_sh(table, altitude_m, f.sun_zenith_rad), local);
}

glm::dvec3 sh_mean_radiance(const ShRadiance& sh) { return kShY00 * sh[0]; }

glm::dvec3 sh_mean_upper_radiance(const ShRadiance& sh) {
  return kShY00 * sh[0] + 0.5 * kShY1 * sh[2];
}

}  // namespace skybake

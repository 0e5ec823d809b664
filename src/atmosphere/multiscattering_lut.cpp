#include "atmosphere/multiscattering_lut.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

struct DirectionIntegrals {
  glm::dvec3 l_prime{0.0};  // L' of eq. 6 (E_I = 1)
  glm::dvec3 l_f{0.0};      // L_f of eq. 8
};

// Eq. 6 and 8 along one direction from `position`, `steps` uniform segments
// sampled at their midpoints, plus the lit ground where the ray ends on it.
DirectionIntegrals integrate_direction(const Atmosphere& atm, const Texture& transmittance_lut,
                                       glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir,
                                       int steps) {
  DirectionIntegrals out;
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
  if (!span.hits_atmosphere) return out;
  glm::dvec3 transmittance(1.0);
  const double dt = (span.t_exit - span.t_enter) / steps;
  for (int i = 0; i < steps && dt > 0.0; ++i) {
    const glm::dvec3 p = position + (span.t_enter + (i + 0.5) * dt) * dir;
    const double r = std::max(glm::length(p), atm.bottom_radius_m);
    const MediumSample medium = sample_medium(atm, r - atm.bottom_radius_m);
    if (medium.extinction == glm::dvec3(0.0)) continue;
    // (1 - exp(-sigma_t dt)) / sigma_t: the energy-conserving segment weight.
    const SegmentWeights w = segment_weights(medium.extinction, dt);
    const glm::dvec3 t_sun =
        lookup_sun_transmittance(transmittance_lut, atm, r, glm::dot(p, sun_dir) / r);
    const glm::dvec3 scattered = transmittance * medium.scattering * w.weight;
    out.l_prime += scattered * t_sun * isotropic_phase();
    out.l_f += scattered;
    transmittance *= w.transmittance;
  }
  if (span.exits_on_ground) {
    const glm::dvec3 up = glm::normalize(position + span.t_exit * dir);
    const double mu_s = clamp_cosine(glm::dot(up, sun_dir));
    if (mu_s > 0.0) {
      const glm::dvec3 t_sun =
          lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius_m, mu_s);
      out.l_prime += transmittance * t_sun * mu_s * atm.ground_albedo / kPi;
    }
  }
  return out;
}

}  // namespace

std::vector<glm::dvec3> fibonacci_sphere_directions(int n) {
  std::vector<glm::dvec3> dirs(std::max(n, 0));
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n;
    const double s = safe_sqrt(1.0 - z * z);
    const double phi = golden_angle * k;
    dirs[k] = {s * std::cos(phi), s * std::sin(phi), z};
  }
  return dirs;
}

MultiscatteringSample compute_multiscattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut, double r,
                                              double mu_s,
                                              const std::vector<glm::dvec3>& directions,
                                              int steps) {
  MultiscatteringSample out;
  if (directions.empty()) return out;
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  const glm::dvec3 position(0.0, 0.0, r);
  const glm::dvec3 sun_dir(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  for (const glm::dvec3& dir : directions) {
    const DirectionIntegrals d =
        integrate_direction(atm, transmittance_lut, position, dir, sun_dir, std::max(steps, 1));
    out.l2 += d.l_prime;
    out.f_ms += d.l_f;
  }
  // Integral over the sphere times p_u: each direction stands for 4 pi / n.
  out.l2 /= double(directions.size());
  out.f_ms /= double(directions.size());
  const glm::dvec3 f = glm::min(out.f_ms, glm::dvec3(kMaxMultiscatteringTransfer));
  out.psi_ms = out.l2 / (1.0 - f);  // eq. 9-10
  return out;
}

glm::dvec2 multiscattering_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                          int height) {
  const double x_mu_s = 0.5 + 0.5 * clamp_cosine(mu_s);
  const double x_h =
      std::clamp((r - atm.bottom_radius_m) / (atm.top_radius_m - atm.bottom_radius_m), 0.0, 1.0);
  return {texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height)};
}

RadiusSunCosine r_mu_s_from_multiscattering_uv(const Atmosphere& atm, glm::dvec2 uv, int width,
                                               int height) {
  const double x_mu_s = unit_from_texel_coord(uv.x, width);
  const double x_h = unit_from_texel_coord(uv.y, height);
  return {atm.bottom_radius_m + x_h * (atm.top_radius_m - atm.bottom_radius_m),
          clamp_cosine(2.0 * x_mu_s - 1.0)};
}

Texture bake_multiscattering_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                 const MultiscatteringLutSpec& spec, const BakeContext& ctx) {
  if (spec.width < 2 || spec.height < 2 || spec.directions < 1 || spec.steps < 1)
    throw Error(
        fmt::format("multiscattering: expected a size of at least 2x2 and at least one "
                    "direction and step, got {}x{}, {} directions, {} steps",
                    spec.width, spec.height, spec.directions, spec.steps));
  Texture tex(spec.width, spec.height, 1, 1, {"R", "G", "B"});
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(spec.directions);
  // Per-row maxima, reduced in row order afterwards: no shared mutable state.
  std::vector<double> row_fms_max(spec.height, 0.0);
  std::vector<int> row_clamped(spec.height, 0);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(0, spec.height, [&](int y) {
    for (int x = 0; x < spec.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, spec.width), texel_center(y, spec.height)}, spec.width,
          spec.height);
      const MultiscatteringSample s =
          compute_multiscattering(atm, transmittance_lut, p.r, p.mu_s, dirs, spec.steps);
      const double fms = std::max({s.f_ms.x, s.f_ms.y, s.f_ms.z});
      row_fms_max[y] = std::max(row_fms_max[y], fms);
      if (fms > kMaxMultiscatteringTransfer) ++row_clamped[y];
      float* t = tex.texel(x, y);
      for (int c = 0; c < 3; ++c) t[c] = float(s.psi_ms[c]);
    }
    progress.tick();
  });
  double fms_max = 0.0;
  int clamped = 0;
  for (int y = 0; y < spec.height; ++y) {
    fms_max = std::max(fms_max, row_fms_max[y]);
    clamped += row_clamped[y];
  }
  Metadata& m = tex.metadata;
  set_meta(m, "parameterization", std::string("hillaire2020_multiscattering"));
  set_meta(m, "u", std::string("texel_coord_from_unit(0.5 + 0.5 * mu_s, width)"));
  set_meta(m, "v",
           std::string("texel_coord_from_unit((r - bottom_radius_m) / "
                       "(top_radius_m - bottom_radius_m), height)"));
  set_meta(m, "texel_coord_from_unit", std::string("0.5 / n + x * (1 - 1 / n)"));
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  set_meta(m, "units", std::string("1/sr (multiply by the sun illuminance)"));
  set_meta(m, "directions", spec.directions);
  set_meta(m, "direction_set", std::string("spherical_fibonacci"));
  set_meta(m, "steps", spec.steps);
  set_meta(m, "fms_max", fms_max);
  set_meta(m, "fms_clamp", kMaxMultiscatteringTransfer);
  set_meta(m, "fms_clamped_texels", clamped);
  return tex;
}

glm::dvec3 lookup_multiscattering(const Texture& lut, const Atmosphere& atm, double r,
                                  double mu_s) {
  const glm::dvec2 uv = multiscattering_uv_from_r_mu_s(atm, r, mu_s, lut.width, lut.height);
  return glm::dvec3(sample_bilinear(lut, uv.x, uv.y, 0, 0, false));
}

}  // namespace skybake

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
                                              double mu_s, const SphereRule& rule, int steps) {
  MultiscatteringSample out;
  if (rule.dirs.empty()) return out;
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  const glm::dvec3 position(0.0, 0.0, r);
  const glm::dvec3 sun_dir(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const bool weighted = !rule.weights.empty();
  for (size_t k = 0; k < rule.dirs.size(); ++k) {
    const DirectionIntegrals d = integrate_direction(atm, transmittance_lut, position,
                                                     rule.dirs[k], sun_dir, std::max(steps, 1));
    const double w = weighted ? rule.weights[k] : 1.0;
    out.l2 += w * d.l_prime;
    out.f_ms += w * d.l_f;
  }
  // Integral over the sphere times p_u: the weights are fractions of 4 pi;
  // without weights each direction stands for 4 pi / n.
  if (!weighted) {
    out.l2 /= double(rule.dirs.size());
    out.f_ms /= double(rule.dirs.size());
  }
  const glm::dvec3 f = glm::min(out.f_ms, glm::dvec3(kMaxMultiscatteringTransfer));
  out.psi_ms = out.l2 / (1.0 - f);  // eq. 9-10
  return out;
}

MultiscatteringSample compute_multiscattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut, double r,
                                              double mu_s,
                                              const std::vector<glm::dvec3>& directions,
                                              int steps) {
  return compute_multiscattering(atm, transmittance_lut, r, mu_s, SphereRule{directions, {}},
                                 steps);
}

SphereRule multiscattering_rule(DirectionQuadrature quadrature, int directions,
                                const Atmosphere& atm, double r) {
  if (quadrature == DirectionQuadrature::fibonacci)
    return {fibonacci_sphere_directions(directions), {}};
  const double ratio = atm.bottom_radius_m / std::max(r, atm.bottom_radius_m);
  const SymmetricGaussShape shape = symmetric_gauss_shape(directions);
  return symmetric_gauss_rule(shape.below, shape.above, shape.azimuths,
                              -safe_sqrt(1.0 - ratio * ratio));
}

namespace {

// The terminator mapping's centre c(r) = mu_h(r) - offset and its atan span.
struct TerminatorFrame {
  double centre, a_lo, a_hi;
};
TerminatorFrame terminator_frame(const MultiscatteringMapping& m, const Atmosphere& atm,
                                 double r) {
  const double ratio = atm.bottom_radius_m / std::max(r, atm.bottom_radius_m);
  const double centre = -safe_sqrt(1.0 - ratio * ratio) - m.offset;
  return {centre, std::atan((-1.0 - centre) / m.width), std::atan((1.0 - centre) / m.width)};
}

// Scattering-weighted mean height of the medium (midpoint rule over the shell).
double scattering_mean_height(const Atmosphere& atm) {
  const double shell = atm.top_radius_m - atm.bottom_radius_m;
  constexpr int kSteps = 4000;
  double weight = 0.0, moment = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double h = (i + 0.5) * shell / kSteps;
    for (const MediumComponent& c : atm.components) {
      const double w = (c.scattering_per_m.x + c.scattering_per_m.y + c.scattering_per_m.z) *
                       density_at(c.density, h);
      weight += w;
      moment += w * h;
    }
  }
  return weight > 0.0 ? moment / weight : 0.5 * shell;
}

}  // namespace

MultiscatteringMapping terminator_mapping(const Atmosphere& atm) {
  const double sigma =
      std::sqrt(std::max(scattering_mean_height(atm), 1e-9) / atm.bottom_radius_m);
  MultiscatteringMapping m;
  m.sun = SunMapping::terminator;
  m.width = kTerminatorWidth * sigma;
  m.offset = kTerminatorOffset * sigma;
  return m;
}

double unit_from_sun_cosine(const MultiscatteringMapping& m, const Atmosphere& atm, double r,
                            double mu_s) {
  mu_s = clamp_cosine(mu_s);
  if (m.sun == SunMapping::linear) return 0.5 + 0.5 * mu_s;
  const TerminatorFrame f = terminator_frame(m, atm, r);
  const double x = (std::atan((mu_s - f.centre) / m.width) - f.a_lo) / (f.a_hi - f.a_lo);
  return std::clamp(x, 0.0, 1.0);
}

double sun_cosine_from_unit(const MultiscatteringMapping& m, const Atmosphere& atm, double r,
                            double x_mu_s) {
  x_mu_s = std::clamp(x_mu_s, 0.0, 1.0);
  if (m.sun == SunMapping::linear) return clamp_cosine(2.0 * x_mu_s - 1.0);
  const TerminatorFrame f = terminator_frame(m, atm, r);
  return clamp_cosine(f.centre + m.width * std::tan(f.a_lo + x_mu_s * (f.a_hi - f.a_lo)));
}

glm::dvec2 multiscattering_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                          int height, const MultiscatteringMapping& mapping) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  const double x_mu_s = unit_from_sun_cosine(mapping, atm, r, mu_s);
  const double x_h = (r - atm.bottom_radius_m) / (atm.top_radius_m - atm.bottom_radius_m);
  return {texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height)};
}

RadiusSunCosine r_mu_s_from_multiscattering_uv(const Atmosphere& atm, glm::dvec2 uv, int width,
                                               int height, const MultiscatteringMapping& mapping) {
  const double x_mu_s = unit_from_texel_coord(uv.x, width);
  const double x_h = unit_from_texel_coord(uv.y, height);
  const double r = atm.bottom_radius_m + x_h * (atm.top_radius_m - atm.bottom_radius_m);
  return {r, sun_cosine_from_unit(mapping, atm, r, x_mu_s)};
}

Texture bake_multiscattering_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                 const MultiscatteringLutSpec& spec, const BakeContext& ctx) {
  if (spec.width < 2 || spec.height < 2 || spec.directions < 1 || spec.steps < 1)
    throw Error(
        fmt::format("multiscattering: expected a size of at least 2x2 and at least one "
                    "direction and step, got {}x{}, {} directions, {} steps",
                    spec.width, spec.height, spec.directions, spec.steps));
  Texture tex(spec.width, spec.height, 1, 1, {"R", "G", "B"});
  const MultiscatteringMapping mapping = spec.sun_mapping == SunMapping::terminator
                                             ? terminator_mapping(atm)
                                             : MultiscatteringMapping{};
  const SphereRule fibonacci = {fibonacci_sphere_directions(spec.directions), {}};
  const bool per_row = spec.quadrature != DirectionQuadrature::fibonacci;
  // Per-row maxima, reduced in row order afterwards: no shared mutable state.
  std::vector<double> row_fms_max(spec.height, 0.0);
  std::vector<int> row_clamped(spec.height, 0);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(0, spec.height, [&](int y) {
    // symmetric_gauss splits at the row's own horizon (r is constant along a row).
    const SphereRule rule =
        per_row ? multiscattering_rule(spec.quadrature, spec.directions, atm,
                                       r_mu_s_from_multiscattering_uv(
                                           atm, {0.5, texel_center(y, spec.height)}, spec.width,
                                           spec.height, mapping)
                                           .r)
                : SphereRule{};
    for (int x = 0; x < spec.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, spec.width), texel_center(y, spec.height)}, spec.width,
          spec.height, mapping);
      const MultiscatteringSample s =
          compute_multiscattering(atm, transmittance_lut, p.r, p.mu_s,
                                  per_row ? rule : fibonacci, spec.steps);
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
  set_multiscattering_axes_metadata(m, mapping, atm);
  set_meta(m, "directions", spec.directions);
  if (spec.quadrature == DirectionQuadrature::fibonacci) {
    set_meta(m, "direction_set", std::string("spherical_fibonacci"));
  } else {
    const SymmetricGaussShape shape = symmetric_gauss_shape(spec.directions);
    set_meta(m, "direction_set", std::string("symmetric_gauss"));
    set_meta(m, "direction_rule",
             fmt::format("Gauss-Legendre zenith cosines, {} on [-1, mu_h(r)] and {} on "
                         "[mu_h(r), 1], x {} midpoint azimuths on (0, pi) weighted twice",
                         shape.below, shape.above, shape.azimuths));
  }
  set_meta(m, "steps", spec.steps);
  set_meta(m, "fms_max", fms_max);
  set_meta(m, "fms_clamp", kMaxMultiscatteringTransfer);
  set_meta(m, "fms_clamped_texels", clamped);
  return tex;
}

void set_multiscattering_axes_metadata(Metadata& m, const MultiscatteringMapping& mapping,
                                       const Atmosphere& atm) {
  set_multiscattering_mapping_metadata(m, mapping);
  set_meta(m, "v",
           std::string("texel_coord_from_unit((r - bottom_radius_m) / "
                       "(top_radius_m - bottom_radius_m), height)"));
  set_meta(m, "texel_coord_from_unit", std::string("0.5 / n + x * (1 - 1 / n)"));
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  set_meta(m, "units", std::string("1/sr (multiply by the sun illuminance)"));
}

void set_multiscattering_mapping_metadata(Metadata& m, const MultiscatteringMapping& mapping) {
  if (mapping.sun == SunMapping::linear) {
    set_meta(m, "mu_s_mapping", std::string("linear"));
    set_meta(m, "u", std::string("texel_coord_from_unit(0.5 + 0.5 * mu_s, width)"));
    return;
  }
  set_meta(m, "mu_s_mapping", std::string("terminator"));
  set_meta(m, "mu_s_mapping_width", mapping.width);
  set_meta(m, "mu_s_mapping_offset", mapping.offset);
  set_meta(m, "u",
           std::string("texel_coord_from_unit((atan((mu_s - c) / w) - atan((-1 - c) / w)) / "
                       "(atan((1 - c) / w) - atan((-1 - c) / w)), width), "
                       "c = -sqrt(1 - (bottom_radius_m / r)^2) - mu_s_mapping_offset, "
                       "w = mu_s_mapping_width"));
}

MultiscatteringMapping multiscattering_mapping_of(const Texture& lut) {
  MultiscatteringMapping m;
  if (!lut.metadata.count("mu_s_mapping")) return m;
  const std::string name = meta_string(lut.metadata, "mu_s_mapping");
  if (name == "linear") return m;
  if (name != "terminator")
    throw Error(fmt::format("multiscattering: unknown mu_s_mapping '{}'", name));
  m.sun = SunMapping::terminator;
  m.width = meta_double(lut.metadata, "mu_s_mapping_width");
  m.offset = meta_double(lut.metadata, "mu_s_mapping_offset");
  return m;
}

glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringMapping& mapping,
                                  const Atmosphere& atm, double r, double mu_s) {
  const glm::dvec2 uv =
      multiscattering_uv_from_r_mu_s(atm, r, mu_s, lut.width, lut.height, mapping);
  return glm::dvec3(sample_bilinear(lut, uv.x, uv.y, 0, 0, false));
}

glm::dvec3 lookup_multiscattering(const Texture& lut, const Atmosphere& atm, double r,
                                  double mu_s) {
  return lookup_multiscattering(lut, multiscattering_mapping_of(lut), atm, r, mu_s);
}

}  // namespace skybake

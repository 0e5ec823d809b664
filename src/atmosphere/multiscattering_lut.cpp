#include "atmosphere/multiscattering_lut.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/direction_march.hpp"
#include "atmosphere/kernels/sunlit_sums.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

// Eq. 6 and 8 along one direction from `position`, `steps` uniform segments
// sampled at their midpoints, without the sun.
void march_direction(const Atmosphere& atm, const Texture& transmittance_lut, glm::dvec3 position,
                     glm::dvec3 dir, int steps, DirectionMarch& out) {
  out.distances.clear();
  out.points.clear();
  out.radii.clear();
  out.sun_reads.clear();
  out.scattered.clear();
  out.l_f = glm::dvec3(0.0);
  out.ground = false;
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
  if (!span.hits_atmosphere) return;
  glm::dvec3 transmittance(1.0);
  const double dt = (span.t_exit - span.t_enter) / steps;
  for (int i = 0; i < steps && dt > 0.0; ++i) {
    const double t = span.t_enter + (i + 0.5) * dt;
    const glm::dvec3 p = position + t * dir;
    const double r = std::max(glm::length(p), atm.bottom_radius_m);
    const MediumSample medium = sample_medium(atm, r - atm.bottom_radius_m);
    if (medium.extinction == glm::dvec3(0.0)) continue;
    // (1 - exp(-sigma_t dt)) / sigma_t: the energy-conserving segment weight.
    const SegmentWeights w = segment_weights(medium.extinction, dt);
    const glm::dvec3 scattered = transmittance * medium.scattering * w.weight;
    out.distances.push_back(t);
    out.points.push_back(p);
    out.radii.push_back(r);
    out.sun_reads.push_back(transmittance_at_radius(transmittance_lut, atm, r));
    out.scattered.push_back(scattered);
    out.l_f += scattered;
    transmittance *= w.transmittance;
  }
  out.t_exit = span.t_exit;
  if (span.exits_on_ground) {
    out.ground = true;
    out.ground_up = glm::normalize(position + span.t_exit * dir);
    out.ground_transmittance = transmittance;
  }
}

// L' of eq. 6 (E_I = 1) of a marched direction under the sun `sun_dir`:
// sigma_s T Vis T_sun p_u per segment, plus the lit ground where the ray ends on it.
glm::dvec3 sunlit_direction(const Atmosphere& atm, const Texture& transmittance_lut,
                            const DirectionMarch& m, glm::dvec3 sun_dir) {
  glm::dvec3 l_prime(0.0);
  for (size_t i = 0; i < m.points.size(); ++i) {
    const glm::dvec3 t_sun =
        lookup_sun_transmittance(transmittance_lut, m.sun_reads[i], atm.bottom_radius_m,
                                 glm::dot(m.points[i], sun_dir) / m.radii[i]);
    l_prime += m.scattered[i] * t_sun * isotropic_phase();
  }
  if (m.ground) {
    const double mu_s = clamp_cosine(glm::dot(m.ground_up, sun_dir));
    if (mu_s > 0.0) {
      const glm::dvec3 t_sun =
          lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius_m, mu_s);
      l_prime += m.ground_transmittance * t_sun * mu_s * atm.ground_albedo / kPi;
    }
  }
  return l_prime;
}

// `from` turned about the zenith through (0, 0, r) onto `dir`, a direction of
// the same zenith cosine: every sample keeps its distance, radius, medium and
// weights; only the points (and so the sun's angle at them) turn.
void turn_march(const DirectionMarch& from, glm::dvec3 position, glm::dvec3 dir,
                DirectionMarch& out) {
  out = from;
  for (size_t i = 0; i < out.points.size(); ++i)
    out.points[i] = position + out.distances[i] * dir;
  if (out.ground) out.ground_up = glm::normalize(position + out.t_exit * dir);
}

// The marches of every direction of `rule` from (0, 0, r). A direction with
// the zenith cosine of the one before it (a ring of the symmetric Gauss rule)
// reuses that march, turned.
void march_directions(const Atmosphere& atm, const Texture& transmittance_lut, double r,
                      const SphereRule& rule, int steps, std::vector<DirectionMarch>& marches) {
  marches.resize(rule.dirs.size());
  const glm::dvec3 position(0.0, 0.0, r);
  for (size_t k = 0; k < rule.dirs.size(); ++k) {
    if (k > 0 && rule.dirs[k].z == rule.dirs[k - 1].z) {
      turn_march(marches[k - 1], position, rule.dirs[k], marches[k]);
    } else {
      march_direction(atm, transmittance_lut, position, rule.dirs[k], std::max(steps, 1),
                      marches[k]);
    }
  }
}

// The sum over the rule's directions of w L' (eq. 5-6) under a sun of
// zenith cosine mu_s (clamped), in the x-z plane.
glm::dvec3 sunlit_sum(const Atmosphere& atm, const Texture& transmittance_lut,
                      const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                      double mu_s) {
  const glm::dvec3 sun_dir(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const bool weighted = !rule.weights.empty();
  glm::dvec3 l2(0.0);
  for (size_t k = 0; k < marches.size(); ++k)
    l2 += (weighted ? rule.weights[k] : 1.0) *
          sunlit_direction(atm, transmittance_lut, marches[k], sun_dir);
  return l2;
}

// The sum over the rule's directions of w L_f (eq. 7-8): the same for
// every sun.
glm::dvec3 transfer_sum(const std::vector<DirectionMarch>& marches, const SphereRule& rule) {
  const bool weighted = !rule.weights.empty();
  glm::dvec3 f_ms(0.0);
  for (size_t k = 0; k < marches.size(); ++k)
    f_ms += (weighted ? rule.weights[k] : 1.0) * marches[k].l_f;
  return f_ms;
}

// Eq. 5-10 from the sums of sunlit_sum and transfer_sum.
MultiscatteringSample multiscattering_from_sums(const std::vector<DirectionMarch>& marches,
                                                const SphereRule& rule, glm::dvec3 l2,
                                                glm::dvec3 f_ms) {
  MultiscatteringSample out;
  out.l2 = l2;
  out.f_ms = f_ms;
  const bool weighted = !rule.weights.empty();
  // Integral over the sphere times p_u: the weights are fractions of 4 pi;
  // without weights each direction stands for 4 pi / n.
  if (!weighted) {
    out.l2 /= double(marches.size());
    out.f_ms /= double(marches.size());
  }
  const glm::dvec3 f = glm::min(out.f_ms, glm::dvec3(kMaxMultiscatteringTransfer));
  out.psi_ms = out.l2 / (1.0 - f);  // eq. 9-10
  return out;
}

// Eq. 5-10 from the marches of `rule` under a sun of zenith cosine mu_s
// (clamped), in the x-z plane.
MultiscatteringSample sunlit_multiscattering(const Atmosphere& atm,
                                             const Texture& transmittance_lut,
                                             const std::vector<DirectionMarch>& marches,
                                             const SphereRule& rule, double mu_s) {
  return multiscattering_from_sums(marches, rule,
                                   sunlit_sum(atm, transmittance_lut, marches, rule, mu_s),
                                   transfer_sum(marches, rule));
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
  if (rule.dirs.empty()) return {};
  std::vector<DirectionMarch> marches;
  march_directions(atm, transmittance_lut, std::clamp(r, atm.bottom_radius_m, atm.top_radius_m),
                   rule, steps, marches);
  return sunlit_multiscattering(atm, transmittance_lut, marches, rule, clamp_cosine(mu_s));
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

MultiscatteringMapping multiscattering_mapping(const MultiscatteringLutSpec& spec,
                                               const Atmosphere& atm) {
  MultiscatteringMapping m =
      spec.sun_mapping == SunMapping::terminator ? terminator_mapping(atm) : MultiscatteringMapping{};
  m.altitude = spec.altitude_mapping;
  return m;
}

double unit_from_radius(const MultiscatteringMapping& m, const Atmosphere& atm, double r) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  const double x = (r - atm.bottom_radius_m) / (atm.top_radius_m - atm.bottom_radius_m);
  return m.altitude == AltitudeMapping::quadratic ? std::sqrt(x) : x;
}

double radius_from_unit(const MultiscatteringMapping& m, const Atmosphere& atm, double x_h) {
  x_h = std::clamp(x_h, 0.0, 1.0);
  const double x = m.altitude == AltitudeMapping::quadratic ? x_h * x_h : x_h;
  return atm.bottom_radius_m + x * (atm.top_radius_m - atm.bottom_radius_m);
}

glm::dvec2 multiscattering_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                          int height, const MultiscatteringMapping& mapping) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  const double x_mu_s = unit_from_sun_cosine(mapping, atm, r, mu_s);
  const double x_h = unit_from_radius(mapping, atm, r);
  return {texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height)};
}

RadiusSunCosine r_mu_s_from_multiscattering_uv(const Atmosphere& atm, glm::dvec2 uv, int width,
                                               int height, const MultiscatteringMapping& mapping) {
  const double x_mu_s = unit_from_texel_coord(uv.x, width);
  const double r = radius_from_unit(mapping, atm, unit_from_texel_coord(uv.y, height));
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
  const MultiscatteringMapping mapping = multiscattering_mapping(spec, atm);
  const SphereRule fibonacci = {fibonacci_sphere_directions(spec.directions), {}};
  const bool per_row = spec.quadrature != DirectionQuadrature::fibonacci;
  // Per-row maxima, reduced in row order afterwards: no shared mutable state.
  std::vector<double> row_fms_max(spec.height, 0.0);
  std::vector<int> row_clamped(spec.height, 0);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(0, spec.height, [&](int y) {
    const double v = multiscattering_texel_uv(spec, 0, y).y;
    // r is constant along a row: its texels share their marches and differ
    // in the sun only; symmetric_gauss splits at the row's own horizon.
    const double r = r_mu_s_from_multiscattering_uv(atm, {0.5, v}, spec.width, spec.height,
                                                    mapping)
                         .r;
    const SphereRule rule =
        per_row ? multiscattering_rule(spec.quadrature, spec.directions, atm, r) : fibonacci;
    std::vector<DirectionMarch> marches;
    march_directions(atm, transmittance_lut, std::clamp(r, atm.bottom_radius_m, atm.top_radius_m),
                     rule, spec.steps, marches);
    // The row's suns, several at a time (direction_march.hpp).
    std::vector<double> mu_s(size_t(spec.width), 0.0);
    for (int x = 0; x < spec.width; ++x)
      mu_s[x] = clamp_cosine(r_mu_s_from_multiscattering_uv(
                                 atm, {multiscattering_texel_uv(spec, x, y).x, v}, spec.width,
                                 spec.height,
                                 mapping)
                                 .mu_s);
    std::vector<glm::dvec3> l2(size_t(spec.width), glm::dvec3(0.0));
    sunlit_sums(atm, transmittance_lut, marches, rule, mu_s.data(), spec.width, l2.data());
    const glm::dvec3 f_ms = transfer_sum(marches, rule);
    for (int x = 0; x < spec.width; ++x) {
      const MultiscatteringSample s = multiscattering_from_sums(marches, rule, l2[x], f_ms);
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
  set_multiscattering_convention_metadata(m, spec.convention);
  return tex;
}

TexelPlacement multiscattering_placement(TableConvention c) {
  return c == TableConvention::hillaire_demo ? TexelPlacement::sub_uv : TexelPlacement::ends;
}

glm::dvec2 multiscattering_texel_uv(const MultiscatteringLutSpec& spec, int x, int y) {
  const TexelPlacement p = multiscattering_placement(spec.convention);
  return {skybake_coord_of_texel(p, x, spec.width), skybake_coord_of_texel(p, y, spec.height)};
}

void set_multiscattering_convention_metadata(Metadata& m, TableConvention c) {
  if (c == TableConvention::skybake) return;
  // Hillaire's GetMultipleScattering reads x at fromUnitToSubUvs(x, n).
  set_meta(m, "convention", std::string(table_convention_name(c)));
  set_meta(m, "texel_coord_from_unit", std::string("(x * n + 0.5) / (n + 1)"));
}

void set_multiscattering_axes_metadata(Metadata& m, const MultiscatteringMapping& mapping,
                                       const Atmosphere& atm) {
  set_multiscattering_mapping_metadata(m, mapping);
  if (mapping.altitude == AltitudeMapping::quadratic) {
    set_meta(m, "altitude_mapping", std::string("quadratic"));
    set_meta(m, "v",
             std::string("texel_coord_from_unit(sqrt((r - bottom_radius_m) / "
                         "(top_radius_m - bottom_radius_m)), height)"));
  } else {
    set_meta(m, "altitude_mapping", std::string("linear"));
    set_meta(m, "v",
             std::string("texel_coord_from_unit((r - bottom_radius_m) / "
                         "(top_radius_m - bottom_radius_m), height)"));
  }
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

namespace {

AltitudeMapping altitude_mapping_of(const Texture& lut) {
  if (!lut.metadata.count("altitude_mapping")) return AltitudeMapping::linear;
  const std::string name = meta_string(lut.metadata, "altitude_mapping");
  if (name == "linear") return AltitudeMapping::linear;
  if (name != "quadratic")
    throw Error(fmt::format("multiscattering: unknown altitude_mapping '{}'", name));
  return AltitudeMapping::quadratic;
}

}  // namespace

MultiscatteringMapping multiscattering_mapping_of(const Texture& lut) {
  MultiscatteringMapping m;
  m.altitude = altitude_mapping_of(lut);
  if (lut.metadata.count("nu_slices")) {
    m.nu_slices = meta_int(lut.metadata, "nu_slices");
    if (lut.metadata.count("zenith_slices")) m.zenith_slices = meta_int(lut.metadata, "zenith_slices");
    if (m.nu_slices < 2 || m.zenith_slices == 1 || m.zenith_slices < 0 ||
        lut.depth != 1 + m.nu_slices + m.zenith_slices || lut.layers != 1)
      throw Error(fmt::format("multiscattering: expected nu_slices >= 2, zenith_slices 0 or "
                              ">= 2 and a volume of 1 + nu_slices + zenith_slices slices, got "
                              "{}, {} and {} slices x {} layers",
                              m.nu_slices, m.zenith_slices, lut.depth, lut.layers));
  }
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

MultiscatteringAtRadius multiscattering_at_radius(const Texture& lut,
                                                  const MultiscatteringMapping& mapping,
                                                  const Atmosphere& atm, double r) {
  // The r half of multiscattering_uv_from_r_mu_s, the same operations.
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  MultiscatteringAtRadius at;
  at.mapping = mapping;
  if (mapping.sun == SunMapping::terminator) {
    const TerminatorFrame f = terminator_frame(mapping, atm, r);
    at.centre = f.centre;
    at.a_lo = f.a_lo;
    at.a_hi = f.a_hi;
  }
  at.row = bilinear_row(lut, texel_coord_from_unit(unit_from_radius(mapping, atm, r), lut.height),
                        0, 0);
  at.u_offset = 0.5 / lut.width;
  at.u_scale = 1.0 - 1.0 / lut.width;
  return at;
}

MultiscatteringView multiscattering_view(const MultiscatteringMapping& mapping, double nu) {
  if (mapping.nu_slices == 0) return {};
  const NodePair p = node_pair(mapping.nu_slices, nu_node_unit_from_cosine(nu));
  return {1 + p.first, p.f};
}

glm::dvec3 lookup_multiscattering_view(const Texture& lut, const MultiscatteringAtRadius& at,
                                       double mu_s, const MultiscatteringView& view,
                                       double mu_v) {
  const double x = multiscattering_sun_unit(at, mu_s);
  const size_t slice = size_t(lut.width) * size_t(lut.height) * size_t(at.row.channels);
  const auto read = [&](int k) {
    const BilinearRow row{at.row.row0 + size_t(k) * slice, at.row.row1 + size_t(k) * slice,
                          at.row.fy, at.row.channels};
    return sample_bilinear_rgb(lut, row, at.u_offset + x * at.u_scale);
  };
  const auto blend = [&](int k, double f) {
    const glm::dvec3 a = read(k), b = read(k + 1);
    return a + f * (b - a);
  };
  glm::dvec3 psi = blend(view.first, view.f);
  if (at.mapping.zenith_slices > 0) {
    const NodePair p =
        node_pair(at.mapping.zenith_slices, zenith_node_unit_from_cosine(mu_v));
    psi += blend(1 + at.mapping.nu_slices + p.first, p.f);
  }
  // The fit can dip below 0 toward views no direction of its grid informed.
  return glm::max(psi, glm::dvec3(0.0));
}

glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringMapping& mapping,
                                  const Atmosphere& atm, double r, double mu_s, double nu,
                                  double mu_v) {
  return lookup_multiscattering(lut, multiscattering_at_radius(lut, mapping, atm, r), mu_s,
                                multiscattering_view(mapping, nu), mu_v);
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

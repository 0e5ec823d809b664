// Multiple-scattering LUT: Psi_ms of Hillaire 2020 section 5.5, the
// luminance transfer (unit 1/sr, multiply by the sun illuminance) of all
// scattering orders >= 2 toward a point, assuming isotropic scattering after
// the first bounce.
//
// Shape: width x height (default 32 x 32), channels R, G, B, float32.
// Axes (texel centres, docs/architecture.md "Texel centres"): the first and
// last texel of each axis sit exactly on the ends of its range,
//   u = texel_coord_from_unit(x_mu_s(r, mu_s), width)       mu_s: sun zenith cosine
//   v = texel_coord_from_unit(x_h(r), height)               r: radius
// with one of two altitude mappings (MultiscatteringMapping, recorded in the
// metadata as altitude_mapping; docs/reference.md "Multiple scattering (Hillaire)"):
//   linear      x_h = (r - Rb) / (Rt - Rb)              (Hillaire 2020 sec. 5.5.2, the default)
//   quadratic   x_h = sqrt((r - Rb) / (Rt - Rb)), rows at r = Rb + (Rt - Rb) x_h^2:
//               rows crowd near the ground, where a low sun's Psi_ms falls
//               fastest with altitude on small planets,
// and one of two sun mappings (recorded as mu_s_mapping):
//   linear      x_mu_s = 0.5 + 0.5 mu_s (Hillaire 2020 sec. 5.5.2, the default)
//   terminator  x_mu_s = (atan((mu_s - c(r)) / w) - a_lo) / (a_hi - a_lo),
//               c(r) = mu_h(r) - offset, mu_h(r) = -sqrt(1 - (Rb / r)^2) the
//               horizon's cosine at r, a_lo / a_hi the same atan at mu_s = -1 / 1:
//               texels crowd where the planet's shadow sweeps over the air
//               around the point and Psi_ms falls by orders of magnitude.
// Per texel, eq. 5-10: over a direction rule of `directions` rays (the
// spherical Fibonacci set, below, or the symmetric Gauss rule,
// DirectionQuadrature), march `steps` uniform segments to
// the ground or the top and accumulate
//   L2   = weighted mean over directions of L'   (eq. 5-6: sigma_s T Vis T_sun p_u per
//          segment, plus the lit ground albedo / pi T_sun max(mu_s, 0) T at a
//          ground hit; E_I = 1)
//   f_ms = weighted mean over directions of L_f  (eq. 7-8: sigma_s T per segment)
// (the mean is the integral over 4 pi times p_u = 1 / (4 pi)); then
//   Psi_ms = L2 / (1 - f_ms)            (eq. 9-10).
// Segments use the energy-conserving integral (sky_integrator.hpp), so per
// direction L_f <= 1 - T(end) < 1 and f_ms < 1; f_ms is still clamped to
// kMaxMultiscatteringTransfer in case rounding brings it to 1, and the
// largest f_ms reached (before the clamp) is written to the metadata as
// `fms_max`, the number of clamped texels as `fms_clamped_texels`.
// Accuracy on Earth against 2048 directions x 200 steps: the direction count
// dominates; within 1.3 % for a sun 17 degrees or more above the horizon, 5 %
// at 6 degrees; around the terminator, where 64 directions resolve the
// planet's shadow coarsely, the relative error grows but stays within 1.5 %
// of the table's largest value.
// Reads: the transmittance LUT (sun transmittance, lookup_transmittance_to_top).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/psi_view_nodes.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

// The axes' mappings (see the opening comment).
enum class SunMapping { linear, terminator };
enum class AltitudeMapping { linear, quadratic };
struct MultiscatteringMapping {
  SunMapping sun = SunMapping::linear;
  AltitudeMapping altitude = AltitudeMapping::linear;
  double width = 1.0;   // terminator: w, the crowded span in mu_s (> 0)
  double offset = 0.0;  // terminator: how far below the horizon's cosine the centre sits
  // A view-dependent table (psi_view_nodes.hpp), a volume: slice 0 the
  // isotropic Psi_ms, slices 1..nu_slices the term a at the nodes of the
  // view-sun cosine nu, then zenith_slices slices of the term b at the nodes
  // of the view's zenith cosine; nu_slices 0: one 2D table.
  int nu_slices = 0;
  int zenith_slices = 0;
};

// The terminator mapping for an atmosphere: with H the scattering-weighted
// mean height of the medium and sigma = sqrt(H / Rb) the width in mu_s over
// which the planet's shadow rises through it (a sun depression delta puts
// the shadow ~Rb delta^2 / 2 above a point, so the lit air thins as
// exp(-delta^2 / (2 sigma^2))), w = kTerminatorWidth sigma and
// offset = kTerminatorOffset sigma.
constexpr double kTerminatorWidth = 4.0;
constexpr double kTerminatorOffset = 0.0;
MultiscatteringMapping terminator_mapping(const Atmosphere& atm);

// The mapping a baked table was made with, from its metadata ("mu_s_mapping",
// "mu_s_mapping_width", "mu_s_mapping_offset", "altitude_mapping"; linear when
// absent; "nu_slices" and "zenith_slices", 0 when absent).
MultiscatteringMapping multiscattering_mapping_of(const Texture& lut);

// x_mu_s in [0, 1] and back: the sun axis before texel centring.
double unit_from_sun_cosine(const MultiscatteringMapping& m, const Atmosphere& atm, double r,
                            double mu_s);
double sun_cosine_from_unit(const MultiscatteringMapping& m, const Atmosphere& atm, double r,
                            double x_mu_s);

// x_h in [0, 1] and back: the altitude axis before texel centring (r clamped
// to the shell).
double unit_from_radius(const MultiscatteringMapping& m, const Atmosphere& atm, double r);
double radius_from_unit(const MultiscatteringMapping& m, const Atmosphere& atm, double x_h);

// The direction rule of eq. 5-8. fibonacci: `directions` equal-weight points
// of the spherical Fibonacci set (below; the paper's "uniformly distributed
// directions"). symmetric_gauss: symmetric_gauss_rule with
// symmetric_gauss_shape(directions), split at the horizon's cosine mu_h(r):
// the integrand is symmetric about the plane of the sun and the zenith, and
// jumps at the horizon (ground or sky), so Gauss-Legendre on each side
// converges where the uniform set needs many times the rays
// (docs/reference.md "Multiple scattering (Hillaire)").
enum class DirectionQuadrature { fibonacci, symmetric_gauss };

struct MultiscatteringLutSpec {
  int width = 32;       // texels along the sun zenith cosine axis (u)
  int height = 32;      // texels along the altitude axis (v)
  int directions = 64;  // ray directions per texel (Hillaire 2020: 64)
  int steps = 20;       // uniform segments per ray (Hillaire 2020 Table 2: 20)
  SunMapping sun_mapping = SunMapping::linear;  // terminator: terminator_mapping(atm)
  AltitudeMapping altitude_mapping = AltitudeMapping::linear;
  DirectionQuadrature quadrature = DirectionQuadrature::fibonacci;
  // Where the texels sit on x_mu_s and x_h (table_convention.hpp): skybake's
  // texel_coord_from_unit, or hillaire_demo's sub-uv reads (linear mappings
  // only).
  TableConvention convention = TableConvention::skybake;
};

// The placement of a multiscattering table's texels on both axes.
TexelPlacement multiscattering_placement(TableConvention c);
// The texture coordinates (skybake's layout, r_mu_s_from_multiscattering_uv's
// input) of the point texel (x, y) of a table of `spec` holds.
glm::dvec2 multiscattering_texel_uv(const MultiscatteringLutSpec& spec, int x, int y);
// Records the convention in a table's metadata (nothing for skybake's):
// "convention" and the texel_coord_from_unit formula its u and v use.
void set_multiscattering_convention_metadata(Metadata& m, TableConvention c);

// The mapping a table of `spec` is baked with for `atm`.
MultiscatteringMapping multiscattering_mapping(const MultiscatteringLutSpec& spec,
                                               const Atmosphere& atm);

// Upper bound applied to f_ms per channel (eq. 9 needs f_ms < 1); F_ms = 1 / (1 - f_ms)
// then stays <= 1e6.
constexpr double kMaxMultiscatteringTransfer = 1.0 - 1e-6;

// The spherical Fibonacci set: point k of n has z_k = 1 - (2k + 1) / n and
// azimuth k * pi (3 - sqrt 5) (the golden angle). Each point stands for an
// equal solid angle 4 pi / n (the z values are the centres of n equal bands,
// and equal z bands have equal area), for any n, deterministic; the z values
// are symmetric about 0, so half the set points down for even n.
std::vector<glm::dvec3> fibonacci_sphere_directions(int n);

struct MultiscatteringSample {
  glm::dvec3 l2{0.0};      // L_2nd order, eq. 5 (1/sr, E_I = 1)
  glm::dvec3 f_ms{0.0};    // eq. 7, unclamped
  glm::dvec3 psi_ms{0.0};  // eq. 10 with f_ms clamped to kMaxMultiscatteringTransfer
};

// Integrates eq. 5-10 from scratch at radius r for a sun of zenith cosine mu_s
// (the sun in the x-z plane, the point on the z axis). Thread-safe.
MultiscatteringSample compute_multiscattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut, double r,
                                              double mu_s,
                                              const std::vector<glm::dvec3>& directions, int steps);

// The same over a weighted direction rule (sphere_rule.hpp).
MultiscatteringSample compute_multiscattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut, double r,
                                              double mu_s, const SphereRule& rule, int steps);

// The rule a bake uses at radius r (the point on the z axis, the sun in the
// x-z plane, as compute_multiscattering puts them).
SphereRule multiscattering_rule(DirectionQuadrature quadrature, int directions,
                                const Atmosphere& atm, double r);

// Texel-centre mapping pair (see the opening comment).
glm::dvec2 multiscattering_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                          int height, const MultiscatteringMapping& mapping = {});
struct RadiusSunCosine {
  double r;     // radius, m
  double mu_s;  // sun zenith cosine
};
RadiusSunCosine r_mu_s_from_multiscattering_uv(const Atmosphere& atm, glm::dvec2 uv, int width,
                                               int height,
                                               const MultiscatteringMapping& mapping = {});

// Bakes the LUT; rows in parallel with tbb::parallel_for, each texel
// independent, so the data does not depend on the thread count. Throws Error
// for sizes below 2x2 or no directions or steps (the preset loader should
// refuse those first).
Texture bake_multiscattering_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                 const MultiscatteringLutSpec& spec, const BakeContext& ctx);

// Psi_ms at radius r (clamped to the shell) and sun zenith cosine mu_s,
// bilinear (1/sr), with the table's own mapping (multiscattering_mapping_of;
// callers reading many points pass it, parsed once).
glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringMapping& mapping,
                                  const Atmosphere& atm, double r, double mu_s);
glm::dvec3 lookup_multiscattering(const Texture& lut, const Atmosphere& atm, double r, double mu_s);

// The parts of lookup_multiscattering that depend on r alone (the altitude
// axis, the terminator mapping's centre and span), worked out once for many
// lookups at one radius.
struct MultiscatteringAtRadius {
  MultiscatteringMapping mapping;
  double centre = 0.0, a_lo = 0.0, a_hi = 0.0;  // terminator: c(r) and the atan span
  BilinearRow row;                              // the table's rows around v(r)
  double u_offset = 0.0, u_scale = 1.0;  // texel_coord_from_unit(x, W) = u_offset + x u_scale
};
MultiscatteringAtRadius multiscattering_at_radius(const Texture& lut,
                                                  const MultiscatteringMapping& mapping,
                                                  const Atmosphere& atm, double r);

// The sun axis's unit coordinate of mu_s at the radius `at` was made for
// (linear, or the terminator mapping).
inline double multiscattering_sun_unit(const MultiscatteringAtRadius& at, double mu_s) {
  mu_s = clamp_cosine(mu_s);
  if (at.mapping.sun != SunMapping::terminator) return 0.5 + 0.5 * mu_s;
  return std::clamp((std::atan((mu_s - at.centre) / at.mapping.width) - at.a_lo) /
                        (at.a_hi - at.a_lo),
                    0.0, 1.0);
}

// lookup_multiscattering(lut, at.mapping, atm, r, mu_s) at the radius `at`
// was made for, bit for bit.
inline glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringAtRadius& at,
                                         double mu_s) {
  const double x = multiscattering_sun_unit(at, mu_s);
  return sample_bilinear_rgb(lut, at.row, at.u_offset + x * at.u_scale);
}

// The nu slices a view of scattering cosine nu (view ray . sun) reads in a
// view-dependent table: `first` and first + 1, weight f on the second
// (psi_view_nodes.hpp); unused for an isotropic table.
struct MultiscatteringView {
  int first = 0;
  double f = 0.0;
};
MultiscatteringView multiscattering_view(const MultiscatteringMapping& mapping, double nu);

// lookup_multiscattering at the radius `at` was made for, read by a view of
// `view` whose zenith cosine at the point is mu_v: the isotropic read for
// an isotropic table, bit for bit; else max(a(nu) + b(mu_v), 0), each term
// the blend of two slices' bilinear reads (psi_view_nodes.hpp).
glm::dvec3 lookup_multiscattering_view(const Texture& lut, const MultiscatteringAtRadius& at,
                                       double mu_s, const MultiscatteringView& view, double mu_v);
inline glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringAtRadius& at,
                                         double mu_s, const MultiscatteringView& view,
                                         double mu_v) {
  if (at.mapping.nu_slices == 0) return lookup_multiscattering(lut, at, mu_s);
  return lookup_multiscattering_view(lut, at, mu_s, view, mu_v);
}

// The same from scratch at (r, mu_s) for a view of scattering cosine nu and
// zenith cosine mu_v at the point.
glm::dvec3 lookup_multiscattering(const Texture& lut, const MultiscatteringMapping& mapping,
                                  const Atmosphere& atm, double r, double mu_s, double nu,
                                  double mu_v);

// Writes the mapping into a table's metadata (name, constants, formulas).
void set_multiscattering_mapping_metadata(Metadata& m, const MultiscatteringMapping& mapping);
// Both axes of a multiscattering table (either model): the sun mapping
// above, the altitude axis, the radii and the units.
void set_multiscattering_axes_metadata(Metadata& m, const MultiscatteringMapping& mapping,
                                       const Atmosphere& atm);

}  // namespace skybake

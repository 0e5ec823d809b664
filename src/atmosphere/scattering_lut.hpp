// Single scattering in Bruneton's 4D table (Bruneton & Neyret 2008 sec. 4;
// Bruneton 2017, atmosphere/functions.glsl "Single scattering"), and what the
// whole precomputed-scattering family (irradiance_lut, scattering_orders,
// scattering3d_lut, gathering_lut) shares: the (r, mu, mu_s, nu) mapping, the
// split of the media into a Rayleigh and a Mie group, the quadrature along a
// view ray, a fast transmittance reader, 4D lookups and the runtime read.
//
// Table: r_size x mu_size x mu_s_size x nu_size (default 32 x 128 x 32 x 8)
// packed into a 3D texture (Bruneton's layout) of width nu_size * mu_s_size,
// height mu_size, depth r_size: texel (x, y, z) holds nu index x / mu_s_size,
// mu_s index x % mu_s_size, mu index y, r index z. float32.
//
// Mapping (Bruneton 2017 GetScatteringTextureUvwzFromRMuMuSNu), Rb / Rt the
// ground / top radii, H = sqrt(Rt^2 - Rb^2), rho = sqrt(r^2 - Rb^2),
// coord(x, n) = 0.5/n + x (1 - 1/n) (texel centres, core/math.hpp):
//   u_r    = coord(rho / H, r_size)
//   u_mu   = rays that hit the ground (lower half of the axis):
//              d = distance to the ground, d_min = r - Rb, d_max = rho,
//              u_mu = 0.5 - 0.5 coord((d - d_min) / (d_max - d_min), mu_size / 2)
//            rays that do not (upper half):
//              d = distance to the top, d_min = Rt - r, d_max = rho + H,
//              u_mu = 0.5 + 0.5 coord((d - d_min) / (d_max - d_min), mu_size / 2)
//   u_mu_s = coord(max(1 - a / A, 0) / (1 + a), mu_s_size), with
//              a = (d(mu_s) - (Rt - Rb)) / (H - (Rt - Rb)), d(mu_s) the distance
//              from the ground to the top along mu_s, A = a(mu_s_min)
//   u_nu   = (nu + 1) / 2, read with a lerp between the nu_size slices
//            (slice k holds nu = -1 + 2 k / (nu_size - 1), not texel centres).
// Why: d spreads the texels evenly in distance, not angle, so the horizon
// (where radiance changes fastest) gets as many texels as the zenith; the two
// halves keep the ground's discontinuity between texels; mu_s stops at
// mu_s_min (default cos 102 deg, Bruneton's Earth value), below which the sky
// is dark. Texel centres sample the boundaries instead of rays past them
// (docs/reference.md "Pitfalls": d < 0 at i / N).
//
// Stored quantities (Bruneton's convention): single scattering is stored
// without its phase function, per group, in units of the sun's irradiance:
//   S_c(r, mu, mu_s, nu) = E_sun int_0^d sigma_s,c(y) T(x, y) T_sun(y) ds,
// c = Rayleigh or Mie; the radiance is p_R(nu) S_R + p_M(nu) S_M.
// Reads: the transmittance LUT (transmittance_lut.hpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "core/bake_context.hpp"
#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

// cos(102 deg): Bruneton's mu_s_min for Earth; cos(120 deg) is the other usual choice.
const double kBrunetonMuSMin = std::cos(102.0 * kPi / 180.0);

struct ScatteringShape {
  int r_size = 32;                    // texels along r (texture depth), >= 2
  int mu_size = 128;                  // texels along mu (texture height), even, >= 4
  int mu_s_size = 32;                 // texels along mu_s, >= 2
  int nu_size = 8;                    // slices along nu, >= 2
  double mu_s_min = kBrunetonMuSMin;  // lowest sun zenith cosine in the table, in (-1, 0]

  int texture_width() const { return nu_size * mu_s_size; }
};

// Throws Error ("expected ..., got ...") when the shape is unusable.
void check_scattering_shape(const ScatteringShape& shape);
// Makes `table` an RGB texture of the packed shape, keeping its buffer (and
// values) when it already is one: for passes that write every texel.
void reuse_rgb_table(Texture& table, const ScatteringShape& shape);
// Metadata keys r_size, mu_size, mu_s_size, nu_size, mu_s_min and back.
void set_scattering_shape_metadata(Metadata& meta, const ScatteringShape& shape);
ScatteringShape scattering_shape_from_metadata(const Metadata& meta);

// Linear interpolation taps along one axis: value = (1 - w) v[i0] + w v[i1].
struct AxisTap {
  int i0 = 0, i1 = 0;
  double w = 0;
};
// Texel-centre axis of n texels, clamp to edge. floor(t) is taken as
// int(t + 1) - 1 (t >= -0.5 here): without SSE4.1, std::floor is a libm call
// and the hottest loops of the bake call this once per texel and node.
inline AxisTap axis_tap(double u, int n) {
  const double t = std::clamp(u, 0.0, 1.0) * n - 0.5;
  const int i = int(t + 1.0) - 1;
  return {std::clamp(i, 0, n - 1), std::clamp(i + 1, 0, n - 1), t - i};
}
// The nu axis: slices at u_nu = k / (nu_size - 1), Bruneton 2017 GetScattering.
inline AxisTap nu_slice_tap(double u_nu, int nu_size) {
  const double x = std::clamp(u_nu, 0.0, 1.0) * (nu_size - 1);
  AxisTap t;
  t.i0 = std::clamp(int(x), 0, nu_size - 1);  // x >= 0: int() is floor()
  t.i1 = std::min(t.i0 + 1, nu_size - 1);
  t.w = t.i0 == t.i1 ? 0.0 : x - t.i0;
  return t;
}

// ---- Mapping (r, mu, mu_s, nu) <-> uvwz ------------------------------------

// (u_nu, u_mu_s, u_mu, u_r) of the opening comment. r is clamped to [Rb, Rt],
// mu_s to [mu_s_min, 1]; ray_hits_ground picks the half of the mu axis
// (ray_intersects_ground(Rb, r, mu) for a ray of the atmosphere).
glm::dvec4 scattering_uvwz_from_r_mu_mu_s_nu(const Atmosphere& atm, const ScatteringShape& shape,
                                             double r, double mu, double mu_s, double nu,
                                             bool ray_hits_ground);
// Its (u_mu, u_r) alone, for loops that read whole (mu_s, nu) rows.
glm::dvec2 scattering_u_mu_r(const Atmosphere& atm, const ScatteringShape& shape, double r,
                             double mu, bool ray_hits_ground);
// The exact inverse. Degenerate rows, where one uvwz stands for many rays:
// at r = Rb every ground ray has d = 0 and comes back as mu = -1; at r = Rt
// every upward ray has d = 0 and comes back as mu = 1.
struct ScatteringParams {
  double r = 0, mu = 0, mu_s = 0, nu = 0;
  bool ray_hits_ground = false;
};
ScatteringParams r_mu_mu_s_nu_from_scattering_uvwz(const Atmosphere& atm,
                                                   const ScatteringShape& shape, glm::dvec4 uvwz);
// The parameters of texel (x, y, z) of the packed texture (Bruneton 2017
// GetRMuMuSNuFromScatteringTextureFragCoord): nu is clamped to the range the
// geometry allows, mu mu_s -+ sqrt((1 - mu^2)(1 - mu_s^2)).
ScatteringParams scattering_texel_params(const Atmosphere& atm, const ScatteringShape& shape, int x,
                                         int y, int z);

// The mu_s coordinate alone (u_mu_s of the mapping) with its constants
// hoisted, for loops where only mu_s changes. Same value as the mapping.
class MuSAxis {
 public:
  MuSAxis(const Atmosphere& atm, const ScatteringShape& shape);
  double u(double mu_s) const { return texel_coord_from_unit(x(mu_s), size_); }
  // axis_tap(u(mu_s), size) without the round trip through u.
  AxisTap tap(double mu_s) const {
    const double t = x(mu_s) * (size_ - 1);
    const int i = std::min(int(t), size_ - 2);
    return {i, i + 1, t - i};
  }
  // tap() of n cosines at once (i0 and w; i1 = i0 + 1), the same values
  // (kernels/sun_taps.hpp): one tap at a time mispredicted its clamps and
  // could not be vectorized (std::sqrt sets errno).
  void taps(const double* mu_s, int n, int* i0, double* w) const;
  // The constants of x(mu_s), for loops that inline taps() (kernels/node_slice_reads.cpp).
  struct Constants {
    double rb, rb2, H2, d_min, inv_span, inv_A, mu_s_min;
    int size;
  };
  Constants constants() const {
    return {rb_, rb2_, H2_, d_min_, inv_span_, inv_A_, mu_s_min_, size_};
  }

 private:
  // std::min / std::max rather than std::clamp: the same value for every
  // non-NaN argument, and no branch.
  double x(double mu_s) const {
    mu_s = std::min(std::max(mu_s, mu_s_min_), 1.0);
    const double d = -rb_ * mu_s + std::sqrt(std::max(rb2_ * mu_s * mu_s + H2_, 0.0));
    const double a = (d - d_min_) * inv_span_;
    return std::min(std::max(std::max(1.0 - a * inv_A_, 0.0) / (1.0 + a), 0.0), 1.0);
  }

  double rb_, rb2_, H2_, d_min_, inv_span_, inv_A_, mu_s_min_;
  int size_;
};

// Every texel's parameters, from per-axis tables: r per z, mu and the ground
// flag per (z, y), mu_s per mu_s index, nu per slice before its clamp.
// params(x, y, z) equals scattering_texel_params(x, y, z) (tests).
struct ScatteringTexelGrid {
  ScatteringShape shape;
  std::vector<double> r, mu, mu_s, nu;
  std::vector<char> ray_hits_ground;

  ScatteringParams params(int x, int y, int z) const;
  // The clamp of nu at (mu, mu_s): mu mu_s -+ spread(mu, mu_s), which params()
  // applies; for loops over the nu slices of one (mu, mu_s).
  static double spread(double mu, double mu_s) {
    return std::sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
  }
};
ScatteringTexelGrid scattering_texel_grid(const Atmosphere& atm, const ScatteringShape& shape);

// ---- The media as the tables split them ------------------------------------

// Components with the Rayleigh phase form the Rayleigh group, the other
// scattering components (Cornette-Shanks or Henyey-Greenstein) the Mie group,
// which must share one phase. Absorbing-only components (ozone) act through
// the transmittance LUT only.
struct ScatteringPhases {
  glm::dvec3 rayleigh_per_m{0.0};  // sum of the group's sigma_s at density 1, 1/m (eq. 19)
  glm::dvec3 mie_per_m{0.0};       // same for the Mie group
  PhaseKind mie_phase = PhaseKind::cornette_shanks;
  double mie_g = 0.0;
  bool has_rayleigh = false, has_mie = false;

  double rayleigh(double nu) const { return phase_function(PhaseKind::rayleigh, 0.0, nu); }
  double mie(double nu) const { return phase_function(mie_phase, mie_g, nu); }
};
// Throws Error when two Mie components have different phases.
ScatteringPhases scattering_phases(const Atmosphere& atm);
// sigma_s (1/m) of each group at altitude h (m).
void scattering_by_group(const Atmosphere& atm, double altitude_m, glm::dvec3& rayleigh,
                         glm::dvec3& mie);

// ---- Quadrature along a view ray -------------------------------------------

// Nodes of the rule for int_0^d f(s) ds along the ray (r, mu). The ray is cut
// at its perigee when it passes one, and every piece is cut into segments
// graded quadratically toward its lowest point (s = end +- L t^2), where
// exponential densities peak, each integrated with 3-point Gauss-Legendre.
// Why not Bruneton's 50-sample trapezoid: on a vertical ray through Mie's
// 1.2 km scale height its 2 km steps are off by ~20 %; this rule is exact
// for constants and within ~5e-6 on Earth's exponentials at 50 nodes
// (tests; 2-point Gauss with as many nodes: 1.3e-4). `nodes` is rounded up
// to a multiple of 3 (segments = ceil(nodes / 3), one at least per piece).
struct RayNode {
  double s;       // distance from the ray's origin, m
  double weight;  // quadrature weight, m
};
void ray_quadrature(double r, double mu, double d, int nodes, std::vector<RayNode>& out);

// The segments of that rule, [a, b] in order of increasing s, tiling [0, d];
// ray_quadrature puts 3-point Gauss-Legendre on each.
struct RaySegment {
  double a, b;  // m from the ray's origin
};
void ray_segments(double r, double mu, double d, int nodes, std::vector<RaySegment>& out);

// 3-point Gauss-Legendre on [-1, 1]: nodes 0, +-sqrt(3/5), weights 8/9, 5/9.
constexpr double kGauss3Nodes[3] = {-0.77459666924148338, 0.0, 0.77459666924148338};
constexpr double kGauss3Weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

// ---- Transmittance ----------------------------------------------------------

// The work arrays of TransmittanceReader::add_sun_products: each sun's
// column, weight and visible fraction.
struct SunTapScratch {
  std::vector<int32_t> i0;
  std::vector<double> w, visible;
};

// The suns seen from one node of a ray (SingleScatteringRay::at_sun): sun k
// is at zenith cosine mu_s[k] and scattering angle cosine nu[k] at the
// ray's start (radius r); at the node, s along the ray and 1 / inv_r from
// the centre, its zenith cosine is clamp_cosine((r mu_s[k] + s nu[k]) inv_r).
struct NodeSuns {
  const double* mu_s;
  const double* nu;
  double r, s, inv_r;
};

// lookup_transmittance_to_top and lookup_transmittance (transmittance_lut.hpp)
// with the work that depends on r alone hoisted into a Row, for inner loops
// that read many mu at one r. The same values up to rounding (tests).
class TransmittanceReader {
 public:
  TransmittanceReader(const Texture& lut, const Atmosphere& atm);

  struct Row {
    const float* row0 = nullptr;  // texel (0, y0) and (0, y1) of the LUT
    const float* row1 = nullptr;
    double wy = 0;
    double r = 0;                    // radius, clamped to [Rb, Rt]
    double d_min = 0, inv_span = 0;  // Rt - r and 1 / (d_max - d_min) of the LUT's mu mapping
    double sun_edge = 0, inv_sun_width = 0;  // sun visibility: smoothstep from mu_s - cos_h = edge
  };
  Row row(double r) const;
  glm::dvec3 to_top(const Row& row, double mu) const {
    const double d = distance_to_top_boundary(rt_, row.r, clamp_cosine(mu));
    const double x_mu = std::clamp((d - row.d_min) * row.inv_span, 0.0, 1.0);
    // Texel-centre coordinate u = coord(x_mu, W) is texel u W - 0.5 = x_mu (W - 1).
    const double t = x_mu * (lut_.width - 1);
    const int i = std::min(int(t), lut_.width - 2);
    const AxisTap tap{i, i + 1, t - i};
    const float* t00 = row.row0 + stride_ * tap.i0;
    const float* t10 = row.row0 + stride_ * tap.i1;
    const float* t01 = row.row1 + stride_ * tap.i0;
    const float* t11 = row.row1 + stride_ * tap.i1;
    glm::dvec3 out;
    for (int c = 0; c < 3; ++c) {
      const double bottom = t00[c] + (t10[c] - double(t00[c])) * tap.w;
      const double top = t01[c] + (t11[c] - double(t01[c])) * tap.w;
      out[c] = bottom + (top - bottom) * row.wy;
    }
    return out;
  }
  glm::dvec3 to_top(double r, double mu) const { return to_top(row(r), mu); }
  // sums[c][k] += a_rayleigh[c] T_k and sums[3 + c][k] += a_mie[c] T_k with
  // T_k = to_sun(row, mu_s_k), mu_s_k sun k's zenith cosine at the node
  // (NodeSuns; the same values: kernels/sun_taps.hpp), for k < n: single
  // scattering's hottest loop (SingleScatteringRay::at_suns).
  void add_sun_products(const Row& row, const NodeSuns& suns, int n, const glm::dvec3& a_rayleigh,
                        const glm::dvec3& a_mie, double* const sums[6],
                        SunTapScratch& scratch) const;
  // Between (r, mu) and the point at distance d along the ray.
  glm::dvec3 between(double r, double mu, double d, bool ray_hits_ground) const;
  // To the sun of zenith cosine mu_s, with the fraction of the sun's disk
  // above the horizon (Bruneton 2017 GetTransmittanceToSun).
  glm::dvec3 to_sun(const Row& row, double mu_s) const {
    // The sun's disk (angular radius alpha) seen from r is cut by the
    // horizon at zenith cosine cos_h; visibility is a smoothstep over
    // mu_s - cos_h in [-sin_h alpha, sin_h alpha] (sin_h = Rb / r).
    const double t = (mu_s - row.sun_edge) * row.inv_sun_width;
    if (t >= 1.0) return to_top(row, mu_s);
    if (t <= 0.0) return glm::dvec3(0.0);
    return (t * t * (3.0 - 2.0 * t)) * to_top(row, mu_s);
  }

 private:
  const Texture& lut_;
  double rb_, rt_, H_, sun_radius_;
  int stride_;  // floats per texel
};

// ---- Single scattering ------------------------------------------------------

struct SingleScattering {
  glm::dvec3 rayleigh{0.0};  // S_R, phase-free, units of sun_illuminance
  glm::dvec3 mie{0.0};       // S_M
};

// The sun-independent part of single scattering along one view ray (nodes,
// the energy-conserving weight x T(x, y) of ray_transfer.hpp x sigma_s(y)
// per group, the transmittance row at each node), for bakers that evaluate
// many suns per ray.
struct SingleScatteringRay {
  struct Node {
    double s = 0, inv_r = 0;  // distance along the ray, 1 / radius
    TransmittanceReader::Row sun_row;
    glm::dvec3 a_rayleigh{0.0}, a_mie{0.0};
  };
  double r = 0;
  std::vector<Node> nodes;  // nodes with a zero contribution are left out
  RayTransfer transfer;

  void prepare(const Atmosphere& atm, const TransmittanceReader& reader, double r, double mu,
               bool ray_hits_ground, int nodes);
  // Bruneton 2017 ComputeSingleScattering for a sun at (mu_s, nu): the sun's
  // cosine at node y is (r mu_s + s nu) / r_y (the local zenith turns along
  // the ray, the sun does not). Multiplied by `sun` (sun_illuminance).
  SingleScattering at_sun(const TransmittanceReader& reader, double mu_s, double nu,
                          glm::dvec3 sun) const;
  // Two suns in one pass over the nodes (the two reads of a node can
  // overlap); out[k] equals at_sun(mu_s[k], nu[k]).
  void at_sun2(const TransmittanceReader& reader, const double mu_s[2], const double nu[2],
               glm::dvec3 sun, SingleScattering out[2]) const;
  // n suns in one pass over the nodes, each node's transmittance to all of
  // them at once (TransmittanceReader::add_sun_products): out[k] equals
  // at_sun(mu_s[k], nu[k]). The work arrays are the caller's, reused.
  struct Scratch {
    std::vector<double> sums;
    SunTapScratch taps;
  };
  void at_suns(const TransmittanceReader& reader, const double* mu_s, const double* nu, int n,
               glm::dvec3 sun, SingleScattering* out, Scratch& scratch) const;
};

// S_R and S_M of one ray from (r, mu) to the ground or the top, for a sun at
// (mu_s, nu), with `nodes` quadrature nodes (ray_transfer). Transmittances
// to the sun come from the LUT, along the view ray from ray_transfer;
// thread-safe.
SingleScattering compute_single_scattering(const Atmosphere& atm, const Texture& transmittance_lut,
                                           double r, double mu, double mu_s, double nu,
                                           bool ray_hits_ground, int nodes);

// The whole table: two RGB textures (shape of the opening comment) of S_R and
// S_M, each texel equal to compute_single_scattering at its parameters. The
// ray's nodes, transmittances and densities are shared by the mu_s x nu
// texels of one (r, mu) row; rows run in parallel (tbb), independent of the
// thread count. Progress per row.
struct SingleScatteringTables {
  Texture rayleigh;
  Texture mie;
};
SingleScatteringTables bake_single_scattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut,
                                              const ScatteringShape& shape, int nodes,
                                              const BakeContext& ctx);

// ---- Lookups ----------------------------------------------------------------

struct ScatteringTaps {
  AxisTap r, mu, mu_s, nu;
};
ScatteringTaps scattering_taps(const ScatteringShape& shape, glm::dvec4 uvwz);
// Quadrilinear read of channels [first, first + 3) of a table in the packed layout.
glm::dvec3 read_scattering(const Texture& table, const ScatteringShape& shape,
                           const ScatteringTaps& taps, int first_channel = 0);
// Quadrilinear read of channels 0..2 at (r, mu, mu_s, nu) (Bruneton 2017
// GetScattering, the lerp between nu slices included).
glm::dvec3 lookup_scattering_rgb(const Texture& table, const ScatteringShape& shape,
                                 const Atmosphere& atm, double r, double mu, double mu_s, double nu,
                                 bool ray_hits_ground);

// The runtime read: radiance (sun_illuminance units, per sr) toward a viewer
// at (r, mu) from the baked textures, p_R(nu) rgb + p_M(nu) mie, where mie
// comes from `single_mie` or, when it is empty, from the alpha channel of a
// combined `scattering` texture (Bodare & Sandberg eq. 19, Bruneton 2017
// GetExtrapolatedSingleMieScattering):
//   mie = rgb * (alpha / rgb.r) * (beta_R.r / beta_M.r) * (beta_M / beta_R).
glm::dvec3 lookup_scattering(const Texture& scattering, const Texture& single_mie,
                             const ScatteringShape& shape, const Atmosphere& atm, double r,
                             double mu, double mu_s, double nu, bool ray_hits_ground);

// One scattering order as the iteration reads it: order 1 from the two
// phase-free single-scattering tables (the phases applied after the lerp, as
// in Bruneton's GetScattering), higher orders from one radiance table.
struct ScatteringOrder {
  const Texture* rayleigh = nullptr;  // order 1: S_R
  const Texture* mie = nullptr;       // order 1: S_M
  const Texture* radiance = nullptr;  // order >= 2: radiance, phase included
  const ScatteringPhases* phases = nullptr;
  // The tables' rows of rays that meet the ground hold the value divided by
  // the ray's opacity 1 - T (incident_radiance.hpp, divide_ground_rows_by_
  // opacity); radiance_at returns that quotient there, and the caller
  // multiplies by the opacity of its own ray.
  bool ground_rows_per_opacity = false;

  glm::dvec3 radiance_at(const Atmosphere& atm, const ScatteringShape& shape, double r, double mu,
                         double mu_s, double nu, bool ray_hits_ground) const;
};

}  // namespace skybake

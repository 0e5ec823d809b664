// The transmittance LUT (Hillaire 2020 sec. 5.2, which reuses Bruneton &
// Neyret 2008 sec. 4; mapping and lookups after Bruneton 2017,
// atmosphere/functions.glsl "Transmittance").
//
// Bakes: width x height (default 256 x 64) float32 texels, channels R, G, B =
// the transmittance at 680, 550 and 440 nm from a point at radius r along a
// ray of zenith cosine mu to the top atmosphere boundary,
//   T(r, mu) = exp(-integral_0^d sigma_t(h(s)) ds),  d = distance to the top.
// Reads: the Atmosphere only (no other product).
//
// Domain: only rays that do not hit the ground, mu from the horizon
// mu_h(r) = -sqrt(1 - Rb^2 / r^2) up to 1. Transmittance along a ray toward
// the ground is obtained from two lookups of reversed rays, which point up
// and so are in the domain (lookup_transmittance, Bruneton's GetTransmittance).
//
// Mapping (docs/reference.md "Transmittance"), u along mu (width), v along r:
//   H = sqrt(Rt^2 - Rb^2)  (distance to the top along the horizon ray at the ground)
//   rho = sqrt(r^2 - Rb^2) (same at radius r), x_r = rho / H
//   d_min = Rt - r, d_max = rho + H, x_mu = (d - d_min) / (d_max - d_min)
//   u = 0.5/W + x_mu (1 - 1/W), v = 0.5/Ht + x_r (1 - 1/Ht)  (W x Ht texels)
// x_mu = 0 is the zenith, x_mu = 1 the horizon; x_r puts more texels near the
// ground, where transmittance varies fastest. Texel centres map to x in
// [0, 1] exactly, so the first and last texels sample the boundaries instead
// of rays past them (sampling at i / N gives d < 0 there, docs/reference.md
// "Pitfalls").
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/extinction_profile.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

struct TransmittanceLutSpec {
  int width = 256;  // texels along mu (u)
  int height = 64;  // texels along r (v)
  int steps = 6;    // quadrature segments per ray (8-point Gauss-Legendre each), >= 1
  // Where the texels sit on x_mu and x_r (table_convention.hpp): skybake's
  // mapping above, or hillaire_demo's texel i at x = (i + 0.5) / n, read at
  // u = x_mu, v = x_r.
  TableConvention convention = TableConvention::skybake;
};

// The placement of a transmittance table's texels on x_mu and x_r.
TexelPlacement transmittance_placement(TableConvention c);

// The rule of compute_optical_depth. gauss3: every component sampled with
// 3-point Gauss-Legendre segments (the reference integrations' rule, 6th
// order). gauss8, the table's: the components whose layers have no
// exponential term (the ozone tent) integrated in closed form
// (atmosphere/linear_layer_depth.hpp), the others sampled with 8-point
// segments (16th order), cut also at x = p, 2.4 p, ... from the perigee and
// graded t^1.25 on rays through their perigee, exp vectorized
// (docs/reference.md "Transmittance").
enum class SegmentRule { gauss3, gauss8 };

// ---- Mapping (r, mu) <-> uv -------------------------------------------------

// Texture coordinates in [0, 1]^2 of (r, mu) in a width x height LUT. r is
// clamped to [Rb, Rt] and mu to [mu_h(r), 1]: a ray below the horizon reads
// the horizon texel. At r = Rt every ray with mu >= 0 has d = 0 and maps to
// the zenith column.
glm::dvec2 transmittance_uv_from_r_mu(const Atmosphere& atm, double r, double mu, int width,
                                      int height);
// The exact inverse: r in [Rb, Rt] (m) and mu in [mu_h(r), 1] (mu = 1 when d = 0).
void r_mu_from_transmittance_uv(const Atmosphere& atm, glm::dvec2 uv, int width, int height,
                                double& r, double& mu);

// ---- Integration from scratch -----------------------------------------------

// Optical depth (dimensionless, RGB) of the segment of length d (m) that starts
// at radius r (m) with zenith cosine mu: integral_0^d sigma_t(h(s)) ds.
// The segment must stay above the ground (altitudes below 0 read the ground's
// density, or with gauss8 the lowest layer's formula). Quadrature: the
// segment is cut at the ray's perigee and where it crosses an altitude at
// which a sampled density profile has a kink (layer boundary, clamp to 0 or
// 1), so every piece is smooth with a monotone altitude; the pieces share
// `steps` segments (at least one each) in proportion to their length,
// graded toward the piece's lowest altitude where exponential densities
// peak, each integrated with the Gauss-Legendre `rule` (see SegmentRule).
// Relative error for Earth with 40 steps of gauss3: ~2e-6, with 6 of gauss8
// (the table's default): ~6e-9 in T (tests).
glm::dvec3 compute_optical_depth(const Atmosphere& atm, double r, double mu, double d, int steps,
                                 SegmentRule rule = SegmentRule::gauss3);

// Optical depth from (r, mu) to the top boundary. Meant for rays that do not
// hit the ground (the grazing ray at the horizon included).
glm::dvec3 compute_optical_depth_to_top(const Atmosphere& atm, double r, double mu, int steps,
                                        SegmentRule rule = SegmentRule::gauss3);

// exp(-optical depth to the top), each channel in [0, 1]. The table's texel
// (x, y) is this at its centre with spec.steps and SegmentRule::gauss8.
glm::dvec3 compute_transmittance_to_top(const Atmosphere& atm, double r, double mu, int steps,
                                        SegmentRule rule = SegmentRule::gauss3);

// compute_transmittance_to_top at each ray (r, mu) = rays[i], the same values
// bit for bit, with the kinks, the extinction profile and the scratch arrays
// worked out once per task instead of per ray (a quarter of the error
// record's time went to that set-up). Parallel over the rays. With
// NodeExp::block the gauss3 rule's node exponentials are exp_block's (within
// 3e-16 relative of std::exp, extinction_profile.hpp), no longer the same
// bits; gauss8 takes exp_block's either way, as the one-ray function.
std::vector<glm::dvec3> compute_transmittances_to_top(const Atmosphere& atm,
                                                      const std::vector<glm::dvec2>& rays,
                                                      int steps,
                                                      SegmentRule rule = SegmentRule::gauss3,
                                                      NodeExp exp_kind = NodeExp::libm);

// ---- Product entry point ----------------------------------------------------

// Bakes the LUT. Rows (v) run in parallel with tbb::parallel_for; every texel is
// computed independently, so the data does not depend on the thread count.
// Reports progress per row. Metadata: the parameterization name
// "bruneton_transmittance", the radii, the size, the step count and the
// mapping formulas, so an engine can decode the table without guessing.
Texture bake_transmittance_lut(const Atmosphere& atm, const TransmittanceLutSpec& spec,
                               const BakeContext& ctx);

// ---- Lookups in a baked LUT -------------------------------------------------

// Transmittance to the top boundary from (r, mu), bilinear with clamp to edge
// (exactly the stored texel at a texel centre). mu below the horizon reads
// the horizon column.
glm::dvec3 lookup_transmittance_to_top(const Texture& lut, const Atmosphere& atm, double r,
                                       double mu);

// The parts of lookup_transmittance_to_top that depend on r alone, worked out
// once for many lookups at one radius (a march's sample seen from many suns).
struct TransmittanceAtRadius {
  double r;             // m, clamped to [Rb, Rt]
  double top_m;         // Rt
  double d_min, d_max;  // the mapping's distance range at r
  BilinearRow row;      // the table's rows around v(r)
  double u_offset, u_scale;  // texel_coord_from_unit(x, W) = u_offset + x u_scale
};
TransmittanceAtRadius transmittance_at_radius(const Texture& lut, const Atmosphere& atm, double r);

// lookup_transmittance_to_top(lut, atm, at.r, mu), bit for bit.
inline glm::dvec3 lookup_transmittance_to_top(const Texture& lut, const TransmittanceAtRadius& at,
                                              double mu) {
  const double d = distance_to_top_boundary(at.top_m, at.r, clamp_cosine(mu));
  const double x_mu = std::clamp((d - at.d_min) / (at.d_max - at.d_min), 0.0, 1.0);
  return sample_bilinear_rgb(lut, at.row, at.u_offset + x_mu * at.u_scale);
}

// Transmittance between the point (r, mu) and the point at distance d (m)
// along the ray (Bruneton 2017 GetTransmittance), each channel in [0, 1]:
//   T(p, q) = T(p -> top) / T(q -> top)                  if the ray misses the ground,
//   T(p, q) = T(q -> top, reversed) / T(p -> top, reversed) if it hits it,
// where the reversed rays (cosines -mu, -mu_d) point up and so are in the LUT.
// ray_hits_ground must be ray_intersects_ground(Rb, r, mu) (the caller usually
// has it). Limit: when the denominator underflowed to 0 in float storage
// (optical depth to the top above ~100, a very dense atmosphere) the ratio is
// undefined; 0 is returned, and such segments should be integrated directly.
glm::dvec3 lookup_transmittance(const Texture& lut, const Atmosphere& atm, double r, double mu,
                                double d, bool ray_hits_ground);

}  // namespace skybake

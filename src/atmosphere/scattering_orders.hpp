// Multiple scattering in Bruneton's 4D table by iterating scattering orders
// (Bruneton & Neyret 2008 sec. 4; Bruneton 2017 functions.glsl "Multiple
// scattering" and model.cc Precompute), and the product entry point that
// bakes the scattering and irradiance textures.
//
// Outputs of bake_bruneton (shapes of scattering_lut.hpp / irradiance_lut.hpp):
//   scattering   width nu*mu_s x height mu x depth r (default 256 x 128 x 32),
//                float32, channels R G B (+ A with combined_mie_alpha):
//                RGB = S_R + sum_{k >= 2} DeltaS_k / p_R(nu), A = S_M.r
//                (Bodare & Sandberg eq. 19, Bruneton's combined texture);
//   single_mie   same shape, R G B = S_M (phase-free single Mie);
//   irradiance   64 x 16, R G B = indirect ground irradiance of the sky
//                orders 1..N (+ direct with irradiance_includes_direct);
//   direct_irradiance 64 x 16, R G B = E_0.
// Runtime radiance toward (r, mu): p_R(nu) RGB + p_M(nu) mie (lookup_scattering).
//
// One order k >= 2 from order k - 1:
//   J_k(x, omega) = sum_c sigma_s,c(x) int p_c(omega . omega') L_{k-1}(x, omega') d omega'
//                   (scattering density, Bruneton ComputeScatteringDensity), where
//                   the incident radiance is the sky of order k - 1 plus, along
//                   rays that meet the ground, T(x, g) albedo / pi E_{k-2}(g)
//                   (E_0 direct sunlight, E_j the indirect irradiance of order j);
//   DeltaS_k(x, omega) = int_0^d T(x, y) J_k(y, omega) ds  (ComputeMultipleScattering),
//                   with the energy-conserving weights of ray_transfer.hpp and J
//                   interpolated as J / sigma_s (density_per_scattering).
//
// How it is made fast (Bruneton evaluates 512 incident directions with a 4D
// lookup each, per texel): the incident
// radiance at (r, mu_s) does not depend on the view direction once the
// direction grid is fixed in the frame of the sun (azimuth measured from the
// sun's vertical plane, not from the view's as in Bruneton), so it is read
// once per (r, mu_s) pair (1024 at default sizes) and shared by its views
// (480 in the sun's frame, 1024 (mu, nu) texels on the table's own). The Rayleigh phase is quadratic in the cosine, so its
// part of J is exact from the field's moments (int L, int omega' omega'^T L);
// only the Mie part loops over the directions per texel. Along view rays the
// nodes, transmittances and (r, mu) interpolation taps are shared by the
// 256 (mu_s, nu) texels of a row.
//
// J_k in the sun's frame (sun_frame_density.hpp, the default): J_k is
// baked per r texel, nu node, mu_s texel and azimuth of the view about the
// sun, not per texel of the 4D table, and the pass along the view rays
// reads it there (kernels/sun_frame_reads.hpp): nu is constant along a ray,
// so a texel whose nu is its slice's reads that slice alone, and J's peak
// around the sun lies along nu instead of across (mu, mu_s) texels. Against
// the path tracer (worst channel): Earth 0.76 -> 0.67 %, Mars 2.80 ->
// 2.24 % (docs/reference.md "Precomputed scattering"). Order 2 is read
// back at midpoints between mu texels against its quadrature
// (mid_texel_error.hpp), for the bake's coarse_table warning.
//
// Storage of orders >= 2 (Bruneton 2017 stores them the same way): in the
// Rayleigh channels, divided by p_R, since the runtime multiplies them by
// p_R(nu). The divisor is p_R at the nu of the texel's slice *before* the
// clamp to the range its mu and mu_s allow, while DeltaS itself is computed
// at the clamped nu. A read lerps slices across neighbouring (mu, mu_s)
// texels with different clamps; dividing by p_R at the clamped nu would make
// the stored DeltaS / p_R of such taps too large, and reads in the sun's
// vertical plane (where nu sits at its bound) up to 18% too bright toward
// the sun (tests/atmosphere/scattering_orders_test.cpp,
// OrdersAboveOneReadBackAsTheOrdersOwnTable; docs/decisions/bruneton-daytime-accuracy.md). With the
// unclamped divisor every (mu, mu_s) texel divides a slice by the same p_R, and the read
// returns lerp(DeltaS) to the curvature of 1 / p_R between slices.
//
// Phase quadrature: each phase's weights over the direction grid are
// normalized per view direction (divided by their sum), so an isotropic
// incident radiance scatters exactly sigma_s L, whatever the grid does to the
// forward Mie peak; this keeps every order energy conserving (tests).
//
// Orders: `orders` in total (1 = single scattering only: exactly orders
// 1..N), or with tolerance > 0 until the residual of an order drops below
// it (at most max_orders).
//
// Geometric tail (tolerance > 0 and geometric_tail, the default): in a
// dense, weakly absorbing sky light escapes only after ~tau^2 scatterings,
// an order changes the table by ~1/k of itself, and stopping when one
// order changes it by less than the tolerance leaves light out (100x Earth
// Rayleigh on a 16x64x16x8 table at tolerance 0.01: blue 16% below the
// path tracer, with the tail 11%; red, which converges, 8%). The orders
// tend to a geometric sequence, DeltaS_{k+1} -> lambda DeltaS_k, lambda the
// dominant eigenvalue of the order-to-order map, one per channel (channels
// are independent problems); so, as successive-orders-of-scattering codes
// do, the orders after the last one N are summed in closed form:
//   sum_{k > N} DeltaS_k = f DeltaS_N,  f = lambda / (1 - lambda),
// lambda_c = sum over texels of DeltaS_N / sum of DeltaS_{N-1}, added to the
// scattering table and the irradiance alike (none when lambda >=
// kMaxTailRatio). Before the sequence is geometric the ratio still grows
// toward lambda, so the tail is an underestimate: it never adds energy the
// orders would not have. The stopping rule is unchanged; the manifest
// records f per channel ("geometric_tail"). Fixed orders stay exactly
// orders 1..N.
// Reads: the transmittance LUT.
#pragma once

#include <vector>

// The steps of one order, each in a header of its own.
#include "atmosphere/geometric_tail.hpp"
#include "atmosphere/incident_radiance.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/multiple_scattering.hpp"
#include "atmosphere/scattering_density.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

constexpr int kMaxScatteringOrders = 1000;

struct BrunetonSpec {
  int r_size = 32;                    // texels along r
  int mu_size = 128;                  // texels along mu, even
  int mu_s_size = 32;                 // texels along mu_s
  int nu_size = 8;                    // slices along nu
  double mu_s_min = kBrunetonMuSMin;  // lowest sun zenith cosine, e.g. cos(120 deg)
  int orders = 4;              // scattering orders, single included, in [1, kMaxScatteringOrders]
  double tolerance = 0.0;      // > 0: stop when an order's residual is below it (relative)
  int max_orders = 100;        // cap when tolerance > 0, in [2, kMaxScatteringOrders]
  bool geometric_tail = true;  // tolerance > 0: sum the orders after the last (header)
  int irradiance_width = 64;   // texels along mu_s
  int irradiance_height = 16;  // texels along r
  bool combined_mie_alpha = true;           // scattering RGBA with single Mie red in A
  bool irradiance_includes_direct = false;  // irradiance = indirect + direct
  int ray_nodes = 51;                       // quadrature nodes per view ray (ray_quadrature)
  int density_directions = 16;     // zenith bands of the density's sphere grid (x 2 azimuths)
  int irradiance_directions = 32;  // zenith bands x 2 of the hemisphere (Bruneton: 32)
  // J_k in the sun's frame (header, "J_k in the sun's frame"); false: on
  // the 4D table's own texels, as Bruneton.
  bool density_in_sun_frame = true;

  ScatteringShape shape() const { return {r_size, mu_size, mu_s_size, nu_size, mu_s_min}; }
};

struct BrunetonTextures {
  Texture scattering;         // RGBA (combined_mie_alpha) or RGB
  Texture single_mie;         // RGB, always filled
  Texture single_rayleigh;    // RGB S_R of order 1 (the single-scattering pass), for measurement
  Texture irradiance;         // RGB
  Texture direct_irradiance;  // RGB
  ScatteringShape shape;
  int orders_used = 0;
  double last_residual = 1.0;     // 1 when only single scattering was baked
  glm::dvec3 tail_factor{0.0};    // f of the geometric tail added, per channel (0: none)
  std::vector<double> residuals;  // of orders 2..orders_used
  double mid_texel_error = -1.0;  // order 2 between mu texels (mid_texel_error.hpp); -1: none
};

// Throws Error ("expected ..., got ...") naming the first bad field.
void check_bruneton_spec(const BrunetonSpec& spec);

// The whole bake. Every stage runs tbb::parallel_for per texel row or
// (r, mu_s) pair, each texel independently: same data for any thread count.
// Progress over the stages; with a tolerance, over the orders the decay of
// the residuals predicts (order_progress.hpp).
BrunetonTextures bake_bruneton(const Atmosphere& atm, const Texture& transmittance_lut,
                               const BrunetonSpec& spec, const BakeContext& ctx);

}  // namespace skybake

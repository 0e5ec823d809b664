// Azimuth-free precomputed scattering: the 3D table of Elek 2009 as used in
// Frostbite (Hillaire 2016 sec. 3.5 and Appendix A) and by Bodare & Sandberg
// 2014 (ch. 4), with orders through a gathering LUT (Bodare & Sandberg
// sec. 4.7.3, gathering_lut.hpp; docs/reference.md "The azimuth-free 3D table").
//
// Shape: width height_size x height view_size x depth sun_size (default
// 32 x 128 x 32), float32; x = altitude h, y = view zenith cosine mu, z = sun
// zenith cosine mu_s. Channels R G B (+ A with combined_mie_alpha):
//   RGB = S_R, A = S_M.r (Bodare & Sandberg eq. 19), or a separate RGB `mie`
//   texture = S_M; radiance at run time = p_R(nu) S_R + p_M(nu) S_M, the
//   phases deferred to the pixel shader (Bodare & Sandberg sec. 4.1).
// Mappings (Hillaire 2016 Appendix A, Yusov 2013; coord(x, n) = 0.5/n + x (1 - 1/n)):
//   u_h  = coord(sqrt(h / H_atm), height_size)                        (eq. 16)
//   u_mu = view cosine against the horizon mu_h = -sqrt(h (2 Rb + h)) / (Rb + h),
//          two halves like Bruneton's (eq. 17, Appendix A Listing 4):
//          above: 0.5 + 0.5 coord(((mu - mu_h) / (1 - mu_h))^0.2, view_size / 2)
//          below: 0.5 coord(((mu_h - mu) / (mu_h + 1))^0.2, view_size / 2)
//   u_s  = coord(0.5 (atan(max(mu_s, mu_s_min) tan(1.26 * 0.75)) / 0.75 + 0.74), sun_size),
//          mu_s_min = tan(-0.74 * 0.75) / tan(1.26 * 0.75) = -0.4481, the image of
//          x = 0 (the listing clamps at -0.45, just below it).
// One deviation from the listing: it keeps mu at least 1e-4 away from the
// horizon, which makes the texels next to the horizon map back to another
// mu (no exact inverse). We keep the exact power law, and the half decides
// whether the ray ends on the ground, as in Bruneton's mapping; the
// geometry is in double and handles the grazing ray.
//
// What a texel holds (the azimuth-free model, phase-free per group c):
//   order 1: S_c = E_sun < int_0^d sigma_s,c(y) T(x, y) T_sun(y) ds >_phi,
//            averaged over azimuth_samples sun azimuths phi around the view
//            (nu = mu mu_s + sqrt((1 - mu^2)(1 - mu_s^2)) cos phi): the best
//            azimuth-free value in the mean square;
//   order k + 1: S_c = int_0^d sigma_s,c(y) T(x, y) G_k(h_y, mu_s_y) ds, G_k the
//            light of order k gathered at y from all directions (gathering_lut),
//            re-scattered isotropically (int p_c = 1 replaces 1/(4 pi) at run time,
//            Bodare & Sandberg eq. 12 and Algorithm 4); mu_s_y = mu_s (r + s mu) / r_y
//            is the sun's cosine at y averaged over azimuth: G is smooth in mu_s,
//            so its azimuthal mean is G at the mean to second order.
// Orders: fixed count or convergence as in scattering_orders.hpp, residual
// = max over texels and channels of DeltaS / max(S, 1e-6 max S), S = S_R + S_M.
// Geometric tail (tolerance > 0 and geometric_tail, the default), as in the
// 4D orders (geometric_tail.hpp): lambda_c = sum of DeltaS_N / sum of
// DeltaS_{N-1} over texels (S_R + S_M, channel c, N >= 3), f = lambda / (1 -
// lambda); f DeltaS_N is added to both groups, and f G_{N-1} to the
// gathering sum (G_N + G_{N+1} + ... = f G_{N-1} under the same ratio), so
// the tables stand for every order. The metadata records f per channel
// ("geometric_tail"). Fixed orders stay exactly orders 1..N.
// Reads: the transmittance LUT.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

extern const double kScattering3dMuSMin;  // tan(-0.74 * 0.75) / tan(1.26 * 0.75)

struct Scattering3dShape {
  int height_size = 32;  // texels along h (x), >= 2
  int view_size = 128;   // texels along mu (y), even, >= 4
  int sun_size = 32;     // texels along mu_s (z), >= 2
};
void check_scattering3d_shape(const Scattering3dShape& shape);

// ---- Mappings (one axis each; the gathering LUT shares h and mu_s) ----------

double scattering3d_u_from_h(const Atmosphere& atm, double h, int n);  // h clamped to [0, H_atm]
double h_from_scattering3d_u(const Atmosphere& atm, double u, int n);
double scattering3d_u_from_mu_s(double mu_s, int n);  // mu_s clamped to [mu_s_min, 1]
double mu_s_from_scattering3d_u(double u, int n);
// mu at altitude h; ray_hits_ground picks the half.
double scattering3d_u_from_mu(const Atmosphere& atm, double h, double mu, bool ray_hits_ground,
                              int n);
double mu_from_scattering3d_u(const Atmosphere& atm, double h, double u, int n,
                              bool& ray_hits_ground);

struct Scattering3dParams {
  double h = 0, mu = 0, mu_s = 0;
  bool ray_hits_ground = false;
};
glm::dvec3 scattering3d_uvw_from_h_mu_mu_s(const Atmosphere& atm, const Scattering3dShape& shape,
                                           double h, double mu, double mu_s, bool ray_hits_ground);
// The exact inverse (at h = 0 every ground ray has d = 0 but keeps its mu).
Scattering3dParams h_mu_mu_s_from_scattering3d_uvw(const Atmosphere& atm,
                                                   const Scattering3dShape& shape, glm::dvec3 uvw);
Scattering3dParams scattering3d_texel_params(const Atmosphere& atm, const Scattering3dShape& shape,
                                             int x, int y, int z);

// ---- Single scattering --------------------------------------------------------

// Order 1 of one texel (the azimuth average above), from scratch; thread-safe.
SingleScattering compute_single_scattering3d(const Atmosphere& atm,
                                             const Texture& transmittance_lut, double h, double mu,
                                             double mu_s, bool ray_hits_ground, int nodes,
                                             int azimuth_samples);

// ---- Product entry point ------------------------------------------------------

struct Scattering3dSpec {
  int height_size = 32;
  int view_size = 128;
  int sun_size = 32;
  int orders = 4;              // scattering orders, single included, in [1, kMaxScatteringOrders]
  double tolerance = 0.0;      // > 0: stop when an order's residual is below it
  int max_orders = 100;        // cap when tolerance > 0
  bool geometric_tail = true;  // tolerance > 0: sum the orders after the last (header)
  bool combined_mie_alpha = true;  // RGBA with S_M.r in A, else a separate `mie` texture
  int ray_nodes = 51;              // quadrature nodes per view ray (ray_quadrature)
  int azimuth_samples = 8;         // sun azimuths averaged in single scattering
  int gathering_directions = 16;   // zenith bands of the gathering sphere (x 2 azimuths), even

  Scattering3dShape shape() const { return {height_size, view_size, sun_size}; }
};

struct Scattering3dTextures {
  Texture scattering;     // RGBA or RGB (see the opening comment)
  Texture mie;            // RGB S_M, always filled
  Texture gathering_sum;  // height_size x sun_size RGB, sum of G_1..G_{N-1} (gathering_lut.hpp)
  // Order 1 alone, phase-free RGB S_R and S_M: what the bake's error
  // measurement reads (the single-scattering part of the table).
  Texture single_rayleigh, single_mie;
  Scattering3dShape shape;
  int orders_used = 0;
  double last_residual = 1.0;     // 1 when only single scattering was baked
  glm::dvec3 tail_factor{0.0};    // f of the geometric tail added, per channel (0: none)
  std::vector<double> residuals;  // of orders 2..orders_used
};

void check_scattering3d_spec(const Scattering3dSpec& spec);

// Rows in parallel (tbb) per stage, every texel independent: same data for
// any thread count. Progress over the orders; with a tolerance, over those
// the decay of the residuals predicts (order_progress.hpp).
Scattering3dTextures bake_scattering3d(const Atmosphere& atm, const Texture& transmittance_lut,
                                       const Scattering3dSpec& spec, const BakeContext& ctx);

// ---- Lookups ----------------------------------------------------------------------

// Trilinear read of channels [first, first + 3), clamp to edge.
glm::dvec3 lookup_scattering3d_rgb(const Texture& table, const Scattering3dShape& shape,
                                   const Atmosphere& atm, double h, double mu, double mu_s,
                                   bool ray_hits_ground, int first_channel = 0);
// Radiance p_R(nu) S_R + p_M(nu) S_M; `mie` empty: S_M from the alpha of a
// combined table (eq. 19, as lookup_scattering).
glm::dvec3 lookup_scattering3d(const Texture& scattering, const Texture& mie,
                               const Scattering3dShape& shape, const Atmosphere& atm, double h,
                               double mu, double mu_s, double nu, bool ray_hits_ground);

}  // namespace skybake

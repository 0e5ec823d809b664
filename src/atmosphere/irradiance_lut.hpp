// Ground irradiance tables (Bruneton & Neyret 2008 sec. 4; Bruneton 2017,
// atmosphere/functions.glsl "Ground irradiance"): the irradiance a horizontal
// surface at radius r receives for a sun of zenith cosine mu_s.
//
// Shape: width x height (default 64 x 16) float32 texels, channels R, G, B,
// x along mu_s, y along r, texel centres at the ends of both ranges:
//   u = coord(0.5 + 0.5 mu_s, width),  v = coord((r - Rb) / (Rt - Rb), height).
// Direct:   E_0(r, mu_s) = E_sun T(r, mu_s) c(mu_s), with c the cosine factor
//           averaged over the sun's disk of angular radius alpha: 0 below
//           -alpha, mu_s above alpha, (mu_s + alpha)^2 / (4 alpha) between
//           (Bruneton 2017 ComputeDirectIrradiance).
// Indirect: E_k(r, mu_s) = int over the upper hemisphere of L_k(r, omega)
//           omega_z d omega, L_k the sky radiance of scattering order k
//           (Bruneton 2017 ComputeIndirectIrradiance).
// Why direct and indirect are separate tables: Bruneton stores the indirect
// part only and adds the direct part at run time from the transmittance LUT,
// because c(mu_s) bends within 2 alpha ~ 0.01 of the horizon while 64 texels
// over [-1, 1] are 0.03 apart, so a stored direct term blurs the sunset on
// the ground. bake_bruneton returns both (scattering_orders.hpp) and an
// option to sum them into one texture for engines that want a single read.
// Reads: the transmittance LUT (direct); a scattering order (indirect).
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

// ---- Mapping (r, mu_s) <-> uv ------------------------------------------------

// r clamped to [Rb, Rt], mu_s to [-1, 1].
glm::dvec2 irradiance_uv_from_r_mu_s(const Atmosphere& atm, double r, double mu_s, int width,
                                     int height);
// The exact inverse.
void r_mu_s_from_irradiance_uv(const Atmosphere& atm, glm::dvec2 uv, int width, int height,
                               double& r, double& mu_s);

// ---- Integration from scratch -----------------------------------------------

// c(mu_s) of the opening comment, for a sun of angular radius alpha (rad).
double sun_average_cosine(double mu_s, double sun_angular_radius_rad);

// E_0 (sun_illuminance units) at (r, mu_s).
glm::dvec3 compute_direct_irradiance(const Atmosphere& atm, const Texture& transmittance_lut,
                                     double r, double mu_s);

// E_k at (r, mu_s) from one scattering order, over the upper hemisphere cut
// into directions/2 zenith bands x 2 directions azimuths (Bruneton: 32 -> 16
// x 64). Each band's weight is its exact integral of cos(theta) d omega, so
// an isotropic radiance L gives pi L exactly; the radiance is read at the
// band's middle. Uses the symmetry of the sky about the sun's vertical plane
// (half the azimuths, twice the weight). Thread-safe.
glm::dvec3 compute_indirect_irradiance(const Atmosphere& atm, const ScatteringShape& shape,
                                       const ScatteringOrder& order, double r, double mu_s,
                                       int directions);

// ---- Tables -----------------------------------------------------------------

// Each texel the function above at its centre; rows in parallel (tbb),
// independent of the thread count.
Texture bake_direct_irradiance(const Atmosphere& atm, const Texture& transmittance_lut, int width,
                               int height, const BakeContext& ctx);
Texture bake_indirect_irradiance(const Atmosphere& atm, const ScatteringShape& shape,
                                 const ScatteringOrder& order, int width, int height,
                                 int directions, const BakeContext& ctx);

// Bilinear read with clamp to edge (the stored texel at a texel centre).
glm::dvec3 lookup_irradiance(const Texture& table, const Atmosphere& atm, double r, double mu_s);

}  // namespace skybake

// Energy balance of a baked 4D or 3D table: a bake-time check that the table
// does not return more light than the sun gives (docs/decisions/warnings.md).
//
// Sun at the zenith, the light leaving the atmosphere is what goes up
// through the top plus what the ground absorbs:
//   out = int_{mu < 0} L(Rt, mu, mu_s = 1, nu = mu) |mu| 2 pi dmu
//         + (1 - albedo) (E_0 + E_sky)(Rb, mu_s = 1),
// and in = E_sun. Absorption in the air makes out / in < 1. A horizontal
// slab would give out = in exactly without absorption; the spherical shell
// reads a little below it (about 1 % for a vacuum, 3 % for a white
// conservative sky; docs/report.md "Dense media need larger tables"). So
// out / in well above 1 can only be the table's own error: a sharp forward
// lobe (Mie of g ~ 0.85) lerped over the mu texels near the zenith gains
// energy order after order.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_orders.hpp"

namespace skybake {

// out / in per channel, sun at the zenith (0 in a channel whose sun is 0).
// Midpoint rule on `cosines` downward cosines at the top.
glm::dvec3 sun_zenith_out_over_in(const Atmosphere& atm, const BrunetonTextures& t,
                                  bool irradiance_includes_direct, int cosines = 2000);

// The same for the azimuth-free 3D table, whose read is exact in azimuth
// with the sun at the zenith; the ground's light from the table's sky
// (int L mu dw over the upper hemisphere, same cosines) and the direct sun
// through the transmittance table.
glm::dvec3 sun_zenith_out_over_in_3d(const Atmosphere& atm, const Scattering3dTextures& t,
                                     const Texture& transmittance_lut, int cosines = 2000);

// A gain above this (out / in - 1, worst channel) is the table's error, not
// the shell's curvature, which only lowers out / in.
constexpr double kEnergyGainTolerance = 0.05;

}  // namespace skybake

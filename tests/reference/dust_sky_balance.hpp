// A sky of dust alone (a Mie group of Henyey-Greenstein phase, no Rayleigh,
// black ground) and its energy balance read from a 4D table
// (mie_lobe_orders_accuracy_test.cpp, mie_lobe_orders_test.cpp its unit
// twin). What the same balance shows at g = 0.85 is in docs/report.md
// ("Where the 4D table's error on Mars comes from").
#pragma once

#include <cmath>

#include <fmt/format.h>

#include "atmosphere/energy_balance.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/orders_resolution.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake::dust_sky_balance {

// Dust of scale height 2 km, vertical scattering optical depth tau (to
// 3e-7) in a 30 km shell, sigma_a = absorption x sigma_s, phase HG g.
inline Atmosphere dust_sky(double tau, double absorption, double g) {
  Atmosphere atm;
  atm.top_radius_m = atm.bottom_radius_m + 30e3;
  atm.ground_albedo = glm::dvec3(0.0);
  const double sigma_s = tau / 2e3;
  atm.components = {fixtures::make_component("dust", glm::dvec3(sigma_s),
                                             glm::dvec3(absorption * sigma_s),
                                             exponential_profile(2e3),
                                             PhaseKind::henyey_greenstein, g)};
  return atm;
}

// Upward flux at the top plus what the black ground absorbs (direct and
// sky), sun at the zenith, over the sun's input, in green: the bake's own
// record of it (atmosphere/energy_balance.hpp).
inline double dust_out_over_in(const Atmosphere& atm, const BrunetonTextures& t) {
  return sun_zenith_out_over_in(atm, t, false).g;
}

}  // namespace skybake::dust_sky_balance

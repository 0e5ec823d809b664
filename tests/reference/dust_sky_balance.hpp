// A sky of dust alone (a Mie group of Henyey-Greenstein phase, no Rayleigh,
// black ground) and its energy balance read from a 4D table
// (mie_lobe_orders_accuracy_test.cpp, mie_lobe_orders_test.cpp its unit
// twin). What the same balance shows at g = 0.85 is in docs/report.md
// ("Where the 4D table's error on Mars comes from").
#pragma once

#include <cmath>

#include <fmt/format.h>

#include "atmosphere/geometry.hpp"
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
// sky), sun at the zenith, over the sun's input: midpoint rule on 2000
// cosines (with the sun at the zenith the table has no azimuth).
inline double dust_out_over_in(const Atmosphere& atm, const BrunetonTextures& t) {
  double up = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double mu = -(i + 0.5) / n;
    up += 2.0 * kPi * (-mu) / n *
          lookup_scattering(t.scattering, t.single_mie, t.shape, atm, atm.top_radius_m, mu, 1.0, mu,
                            ray_intersects_ground(atm.bottom_radius_m, atm.top_radius_m, mu))
              .g;
  }
  const double ground = (lookup_irradiance(t.direct_irradiance, atm, atm.bottom_radius_m, 1.0) +
                         lookup_irradiance(t.irradiance, atm, atm.bottom_radius_m, 1.0))
                            .g;
  return (up + ground) / atm.sun_illuminance.g;
}

}  // namespace skybake::dust_sky_balance

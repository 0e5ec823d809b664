// Tests of the transmittance table's rule (compute_optical_depth with
// SegmentRule::gauss8, atmosphere/transmittance_lut.hpp) where it departs
// from the reference rule: the cuts around the perigee of a ray grazing a
// small planet, and the exponentials whose exponent leaves the range of the
// vectorized exp. The closed form of linear layers is tested in
// linear_layer_depth_test.cpp.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

// A 1 km planet under 100 km of Earth's air (presets/extreme/planet_1km):
// near the perigee of a grazing ray the radius sqrt(x^2 + p^2) bends over
// ~p = 1 km, much less than the ray's 100 km. Rays with their perigee at the
// ground (the horizon), 10 m and 500 m above it, seen from several
// altitudes: at the default 6 segments the table's rule is within 1e-9 of
// the 3-point rule at 4000 segments (without the cuts at x = p, 2.4 p, ...
// it is off by up to 1e-5).
TEST(TableRule, ConvergedOnRaysGrazingASmallPlanet) {
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.bottom_radius_m = 1e3;
  atm.top_radius_m = 101e3;
  for (double h : {0.0, 500.0, 3e3, 14e3, 40e3, 90e3}) {
    const double r = atm.bottom_radius_m + h;
    for (double perigee_h : {0.0, 10.0, 500.0}) {
      const double p = atm.bottom_radius_m + perigee_h;
      if (p > r) continue;
      const double mu = -std::sqrt(std::max(0.0, 1.0 - (p / r) * (p / r)));
      const glm::dvec3 table = compute_optical_depth_to_top(atm, r, mu, 6, SegmentRule::gauss8);
      const glm::dvec3 fine = compute_optical_depth_to_top(atm, r, mu, 4000);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(table[c], fine[c], 1e-9 * fine[c]) << "h " << h << " perigee " << perigee_h;
    }
  }
}

// A 100 m scale height under 100 km of air: exp(-h / H) reaches e^-1000,
// past the vectorized exp's range, so that component keeps std::exp. Along
// the vertical the optical depth is sigma H (exp(-h0 / H) - exp(-Ht / H)).
TEST(TableRule, SteepExponentialAlongTheVertical) {
  const double sigma = 1e-3, H = 100.0;
  const Atmosphere atm =
      fixtures::single_component_atmosphere(glm::dvec3(sigma), exponential_profile(H));
  const double top_h = atm.top_radius_m - atm.bottom_radius_m;
  for (double h0 : {0.0, 50.0, 2e3}) {
    const double exact = sigma * H * (std::exp(-h0 / H) - std::exp(-top_h / H));
    const double tau =
        compute_optical_depth_to_top(atm, atm.bottom_radius_m + h0, 1.0, 64, SegmentRule::gauss8).r;
    EXPECT_TRUE(std::isfinite(tau));
    EXPECT_NEAR(tau, exact, 1e-9 * exact) << "h0 " << h0;
  }
}

}  // namespace
}  // namespace skybake

// The rule that gives skies whose multiple scattering carries Mie's forward
// lobe the finer 4D shape (orders_resolution.hpp): the groups' vertical
// scattering optical depths against their closed forms, and which presets
// the rule picks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "atmosphere/orders_resolution.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(OrdersResolution, VerticalDepthsMatchTheExponentialsClosedForm) {
  // int_0^top sigma e^(-h / H) dh = sigma H (1 - e^(-top / H)).
  const Atmosphere atm = fixtures::earth_atmosphere();
  const GroupScatteringDepths d = vertical_scattering_depths(atm);
  const double top = atm.top_radius_m - atm.bottom_radius_m;
  const glm::dvec3 rayleigh = glm::dvec3(5.802e-6, 13.558e-6, 33.1e-6) * 8e3 *
                              (1.0 - std::exp(-top / 8e3));
  const double mie = 3.996e-6 * 1.2e3 * (1.0 - std::exp(-top / 1.2e3));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(d.rayleigh[c], rayleigh[c], 1e-4 * rayleigh[c]);
    EXPECT_NEAR(d.mie[c], mie, 1e-4 * mie);
  }
}

TEST(OrdersResolution, MarsDustShapesItsOrdersEarthAndTheTinyPlanetDoNot) {
  const std::string presets = std::string(SKYBAKE_SOURCE_DIR) + "/presets/";
  EXPECT_TRUE(mie_shapes_multiple_scattering(load_scene(presets + "mars.json").atmosphere));
  EXPECT_FALSE(mie_shapes_multiple_scattering(load_scene(presets + "earth.json").atmosphere));
  EXPECT_FALSE(mie_shapes_multiple_scattering(load_scene(presets + "tiny_planet.json").atmosphere));
  // Dust alone: no Rayleigh group at all.
  Atmosphere dust = fixtures::earth_atmosphere();
  dust.components = {fixtures::earth_mie()};
  EXPECT_TRUE(mie_shapes_multiple_scattering(dust));
}

TEST(OrdersResolution, LobeShapeKeepsTheOtherSettings) {
  BrunetonSpec spec;
  spec.tolerance = 1e-3;
  spec.density_directions = 24;
  const BrunetonSpec lobe = with_mie_lobe_shape(spec);
  EXPECT_EQ(lobe.r_size, 32);
  EXPECT_EQ(lobe.mu_size, 128);
  EXPECT_EQ(lobe.mu_s_size, 64);
  EXPECT_EQ(lobe.nu_size, 16);
  EXPECT_EQ(lobe.tolerance, 1e-3);
  EXPECT_EQ(lobe.density_directions, 24);
  check_bruneton_spec(lobe);
}

}  // namespace
}  // namespace skybake

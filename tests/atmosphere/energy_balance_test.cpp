// The bake-time energy balance (atmosphere/energy_balance.hpp): the 4D and
// the azimuth-free 3D tables of one sky reach it by different reads (the
// irradiance table; the 3D sky's hemisphere and the direct sun through the
// transmittance table) and must agree; a vacuum sends every ray of sunlight
// to the ground.
#include "atmosphere/energy_balance.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "atmosphere/transmittance_lut.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(EnergyBalance, FourDAndThreeDTablesOfEarthAgree) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {256, 64, 40}, BakeContext{});
  BrunetonSpec four;
  four.r_size = 16, four.mu_size = 64, four.mu_s_size = 16, four.nu_size = 8;
  const BrunetonTextures t4 = bake_bruneton(atm, lut, four, BakeContext{});
  Scattering3dSpec three;
  three.height_size = 16, three.view_size = 64, three.sun_size = 16;
  const Scattering3dTextures t3 = bake_scattering3d(atm, lut, three, BakeContext{});
  const glm::dvec3 a = *find_meta<glm::dvec3>(t4.scattering.metadata, "energy_out_over_in");
  const glm::dvec3 b = *find_meta<glm::dvec3>(t3.scattering.metadata, "energy_out_over_in");
  EXPECT_EQ(a, sun_zenith_out_over_in(atm, t4, four.irradiance_includes_direct));
  EXPECT_EQ(b, sun_zenith_out_over_in_3d(atm, t3, lut));
  for (int c = 0; c < 3; ++c) {
    RecordProperty(fmt::format("out_over_in_{}", c), fmt::format("{:.4f} / {:.4f}", a[c], b[c]));
    EXPECT_NEAR(a[c], b[c], 0.01) << c;
    // Ozone and Mie absorb: less comes out than went in, and most does.
    EXPECT_LT(a[c], 1.0) << c;
    EXPECT_GT(a[c], 0.7) << c;
  }
}

TEST(EnergyBalance, VacuumSendsTheSunToTheGround) {
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.components.clear();
  atm.ground_albedo = glm::dvec3(0.0);
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 40}, BakeContext{});
  BrunetonSpec spec;
  spec.r_size = 4, spec.mu_size = 16, spec.mu_s_size = 8, spec.nu_size = 4, spec.orders = 2;
  const BrunetonTextures t = bake_bruneton(atm, lut, spec, BakeContext{});
  const glm::dvec3 ratio = sun_zenith_out_over_in(atm, t, spec.irradiance_includes_direct);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ratio[c], 1.0, 1e-3) << c;
}

}  // namespace
}  // namespace skybake

// The energy balance of a sky of dust alone at the 4D shape of
// orders_resolution.hpp (dust_sky_balance.hpp), conservative and absorbing;
// the unit twin is mie_lobe_orders_test.cpp.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "reference/dust_sky_balance.hpp"

namespace skybake {
namespace {

using dust_sky_balance::dust_out_over_in;
using dust_sky_balance::dust_sky;

TEST(MieLobeOrders, DustSkyBalancesItsEnergy) {
  // Conservative dust over a black ground returns all the sunlight (up at
  // the top + absorbed by the ground = E) to the table's interpolation and
  // the shell's curvature (measured 0.987 at g = 0.5, 0.993 at g = 0); with
  // sigma_a = 0.1 sigma_s the medium keeps some: less comes out.
  for (double g : {0.0, 0.5}) {
    double conservative = 0.0;
    for (double absorption : {0.0, 0.1}) {
      SCOPED_TRACE(fmt::format("g {} sigma_a / sigma_s {}", g, absorption));
      const Atmosphere atm = dust_sky(0.5, absorption, g);
      ASSERT_TRUE(mie_shapes_multiple_scattering(atm));
      const Texture lut = bake_transmittance_lut(atm, {256, 64, 40}, BakeContext{});
      BrunetonSpec spec = with_mie_lobe_shape(BrunetonSpec{});
      spec.r_size = 16, spec.mu_size = 64;  // the lobe's angular axes, a cut-down r and mu
      spec.combined_mie_alpha = false;
      spec.tolerance = 1e-3;
      const BrunetonTextures t = bake_bruneton(atm, lut, spec, BakeContext{});
      EXPECT_LT(t.last_residual, spec.tolerance);
      const double ratio = dust_out_over_in(atm, t);
      RecordProperty(fmt::format("out_over_in_g{}_a{}", g, absorption), fmt::format("{:.4f}", ratio));
      EXPECT_LT(ratio, 1.0 + 1e-3);
      if (absorption == 0.0) {
        EXPECT_GT(ratio, 0.975);
        conservative = ratio;
      } else {
        EXPECT_LT(ratio, conservative - 0.01);
      }
    }
  }
}

}  // namespace
}  // namespace skybake

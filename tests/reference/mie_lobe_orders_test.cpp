// The dust sky's energy balance (mie_lobe_orders_accuracy_test.cpp) cut
// down for the unit tier: conservative dust of g = 0.5 on an 8 x 32 x 64 x
// 16 table (the lobe's angular axes) returns the sunlight it receives, and
// the bake records it; dust of g = 0.85 on the same mu axis gains energy,
// and the bake's record shows it (the energy_gain warning's number).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/orders_resolution.hpp"
#include "reference/dust_sky_balance.hpp"

namespace skybake {
namespace {

// Conservative dust of vertical optical depth 0.5 and phase asymmetry g on
// the small table, converged to 1e-3.
BrunetonTextures small_dust_table(const Atmosphere& atm) {
  const Texture lut = bake_transmittance_lut(atm, {128, 32, 40}, BakeContext{});
  BrunetonSpec spec = with_mie_lobe_shape(BrunetonSpec{});
  spec.r_size = 8, spec.mu_size = 32;
  spec.combined_mie_alpha = false;
  spec.tolerance = 1e-3;
  return bake_bruneton(atm, lut, spec, BakeContext{});
}

TEST(MieLobeOrders, ConservativeDustSkyReturnsTheSunlightOnASmallTable) {
  // Measured 0.974; the table's interpolation and the shell's curvature
  // take the rest.
  const Atmosphere atm = dust_sky_balance::dust_sky(0.5, 0.0, 0.5);
  const BrunetonTextures t = small_dust_table(atm);
  const double ratio = dust_sky_balance::dust_out_over_in(atm, t);
  RecordProperty("out_over_in", fmt::format("{:.4f}", ratio));
  EXPECT_LT(ratio, 1.0 + 1e-3);
  EXPECT_GT(ratio, 0.96);
  for (const Texture* table : {&t.scattering, &t.irradiance}) {
    const glm::dvec3* recorded = find_meta<glm::dvec3>(table->metadata, "energy_out_over_in");
    ASSERT_NE(recorded, nullptr);
    EXPECT_DOUBLE_EQ(recorded->g, ratio);
  }
}

TEST(MieLobeOrders, ForwardDustOnACoarseMuAxisRecordsItsGain) {
  // docs/report.md: 1.34 at 32 mu texels (Henyey-Greenstein, g = 0.85).
  const BrunetonTextures t = small_dust_table(dust_sky_balance::dust_sky(0.5, 0.0, 0.85));
  const glm::dvec3* recorded = find_meta<glm::dvec3>(t.scattering.metadata, "energy_out_over_in");
  ASSERT_NE(recorded, nullptr);
  RecordProperty("out_over_in", fmt::format("{:.4f}", recorded->g));
  EXPECT_GT(recorded->g, 1.0 + kEnergyGainTolerance);
}

TEST(MieLobeOrders, TablesFromAFieldThatGainsEnergyRecordItsBalance) {
  // The converged Psi_ms table reads the same kind of iteration: its
  // metadata carries the field's balance, which the energy_gain warning reads.
  const Atmosphere atm = dust_sky_balance::dust_sky(0.5, 0.0, 0.85);
  const Texture lut = bake_transmittance_lut(atm, {128, 32, 40}, BakeContext{});
  ConvergedMultiscatteringSpec spec;
  spec.bruneton = with_mie_lobe_shape(spec.bruneton);
  spec.bruneton.r_size = 8, spec.bruneton.mu_size = 32;
  const ConvergedField field = compute_converged_field(atm, lut, spec, BakeContext{});
  EXPECT_GT(field.energy_out_over_in.g, 1.0 + kEnergyGainTolerance);
  MultiscatteringLutSpec table;
  table.width = table.height = 8;
  const Texture psi = converged_multiscattering_table(atm, lut, table, spec, field, BakeContext{});
  const glm::dvec3* recorded = find_meta<glm::dvec3>(psi.metadata, "energy_out_over_in");
  ASSERT_NE(recorded, nullptr);
  EXPECT_EQ(*recorded, field.energy_out_over_in);
}

}  // namespace
}  // namespace skybake

// The sky-light products' radiance source; see the header.
#include "atmosphere/sky_light_source.hpp"

#include "atmosphere/order_progress.hpp"

namespace skybake {

ConvergedMultiscatteringSpec twilight_field_spec(const ConvergedMultiscatteringSpec& daylight) {
  ConvergedMultiscatteringSpec c;
  BrunetonSpec& b = c.bruneton;
  // 64 sun cosines, 4x the daylight field's; r, mu and nu at half of it
  // and the density's sphere coarse too, as the table below averages over
  // directions. The ground's irradiance has 512 sun cosines, 0.2 degrees
  // apart at the horizon: below it that light falls about 2x a degree, and
  // read between 64 (1.8 degrees apart) it was up to 1.9x too bright, which
  // the density passed on to the sky (Earth's light of orders >= 2 4 degrees
  // into twilight 20 % too bright at the ground, 3 % with 512). It keeps
  // the default 32 directions: a 32 x 8 table from 16 left Earth's sky 4
  // degrees into twilight 9 % off, not 5
  // (docs/decisions/sky-irradiance-source.md).
  b.r_size = 8;
  b.mu_size = 32;
  b.mu_s_size = 64;
  b.nu_size = 8;
  b.density_directions = 8;
  b.ray_nodes = 25;
  b.irradiance_width = 512;
  b.tolerance = daylight.bruneton.tolerance;
  c.estimator = PsiEstimator::relative;
  c.bands = 8;
  c.nu_slices = 8;
  c.zenith_slices = 8;
  return c;
}

MultiscatteringLutSpec twilight_psi_table_spec() {
  // The sun axis crowded at the terminator, the altitudes near the ground
  // where the twilight viewers' rays cross the densest air: 16 such rows
  // take Earth's ground from 15 / 53 / 74 % RMS to 9 / 44 / 75 % with the
  // sun 4 / 11 / 18 degrees down, against 32 rows spaced evenly.
  MultiscatteringLutSpec t;
  t.width = 64;
  t.height = 16;
  t.sun_mapping = SunMapping::terminator;
  t.altitude_mapping = AltitudeMapping::quadratic;
  return t;
}

void make_sky_light_source(SkyLightSource& out, const Atmosphere& atm,
                           const Texture& transmittance_lut, const SkyLightSourceSpec& spec,
                           const BakeContext& ctx) {
  out.field = compute_converged_field(atm, transmittance_lut, spec.field,
                                      stage_context(ctx, 0.0, spec.twilight ? 0.7 : 1.0));
  out.source = SkyRadianceSource{};
  out.source.transmittance = &transmittance_lut;
  out.source.field = &out.field;
  if (!spec.twilight) return;
  const ConvergedMultiscatteringSpec twilight = twilight_field_spec(spec.field);
  out.twilight_field =
      compute_converged_field(atm, transmittance_lut, twilight, stage_context(ctx, 0.7, 0.9));
  out.twilight_psi = converged_multiscattering_table(atm, transmittance_lut,
                                                     twilight_psi_table_spec(), twilight,
                                                     out.twilight_field, stage_context(ctx, 0.9, 1.0));
  out.twilight = psi_ms_source(atm, transmittance_lut, out.twilight_psi, spec.rays);
  out.source.below_horizon = &out.twilight;
}

}  // namespace skybake

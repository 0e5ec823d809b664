// The sky-light products' radiance source; see the header.
#include "atmosphere/sky_light_source.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/order_progress.hpp"

namespace skybake {
namespace {

// What the two twilight fields share, on the converged default: 32 view
// zeniths, 8 nu slices, 25 ray nodes, the ground's irradiance on 512 sun
// cosines (psi_view_field_spec says why), the daylight field's tolerance,
// and J_k on the table's own texels: in the sun's frame (scattering_orders.hpp)
// the twilight decode moved from 5.8 to 6.7 % RMS on Earth's ground 11
// degrees down and from 2.6 / 9.0 to 3.3 / 12.8 % on Mars's 4 and 11
// degrees down (the tiny planet 1.4 / 1.5 -> 1.1 / 1.2 %), with 8 or 32
// azimuths alike.
ConvergedMultiscatteringSpec twilight_base(const ConvergedMultiscatteringSpec& daylight,
                                           int r_size, int mu_s_size, int density_directions) {
  ConvergedMultiscatteringSpec c;
  BrunetonSpec& b = c.bruneton;
  b.r_size = r_size;
  b.mu_size = 32;
  b.mu_s_size = mu_s_size;
  b.nu_size = 8;
  b.density_directions = density_directions;
  b.ray_nodes = 25;
  b.irradiance_width = 512;
  b.tolerance = daylight.bruneton.tolerance;
  b.density_in_sun_frame = false;
  return c;
}

}  // namespace

ConvergedMultiscatteringSpec twilight_field_spec(const ConvergedMultiscatteringSpec& daylight,
                                                 double deepest_sun_zenith_rad) {
  // Against the path tracer at 1024 paths a ray (converged there up to
  // 11 degrees down), RMS at the ground 4 / 11 / 18 degrees down, this
  // field against psi_ms_by_view: Earth 1.8 / 5.8 / 60% against 2.4 / 20 /
  // 73%, Mars 2.6 / 9.0 / 9.2% against 2.6 / 8.0 / 15%, the tiny planet
  // 1.4 / 1.5 / 2.2% against 1.4 / 1.2 / 1.8%. Earth 11 degrees down
  // (docs/decisions/sky-irradiance-source.md): 16% from 8 x 32 x 64 x 8,
  // 5.6% with 16 radii, 128 sun cosines and 16 density bands; nu 16 would
  // gain 0.5 point for 1.5x the cost, mu 64 and nu 16 0.6-3 points on Mars
  // for 2.3x Mars's cost. The sun axis reaching 6 degrees
  // past the deepest sun keeps 18 degrees down from reading the axis's
  // edge (11x too bright). Its tolerance is 10x the daylight field's: the
  // geometric tail carries the rest, the figures above move by under 0.1
  // point, and the bake takes 0.45 s less on Earth (3x: the tiny planet
  // 0.3 point worse).
  ConvergedMultiscatteringSpec c = twilight_base(daylight, 16, 128, 16);
  c.bruneton.tolerance *= 10.0;
  c.mu_s_min_cap = std::cos(std::min(deepest_sun_zenith_rad + 6.0 * kDeg, 179.0 * kDeg));
  return c;
}

ConvergedMultiscatteringSpec psi_view_field_spec(const ConvergedMultiscatteringSpec& daylight) {
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
  ConvergedMultiscatteringSpec c = twilight_base(daylight, 8, 64, 8);
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
  const bool second = spec.twilight != TwilightSource::daylight_field;
  out.field = compute_converged_field(atm, transmittance_lut, spec.field,
                                      stage_context(ctx, 0.0, second ? 0.7 : 1.0));
  out.source = SkyRadianceSource{};
  out.source.transmittance = &transmittance_lut;
  out.source.field = &out.field;
  if (!second) return;
  out.twilight = SkyRadianceSource{};
  if (spec.twilight == TwilightSource::twilight_field) {
    out.twilight_field = compute_converged_field(
        atm, transmittance_lut, twilight_field_spec(spec.field, spec.deepest_sun_zenith_rad),
        stage_context(ctx, 0.7, 1.0));
    out.twilight.transmittance = &transmittance_lut;
    out.twilight.field = &out.twilight_field;
  } else {
    const ConvergedMultiscatteringSpec coarse = psi_view_field_spec(spec.field);
    out.twilight_field =
        compute_converged_field(atm, transmittance_lut, coarse, stage_context(ctx, 0.7, 0.9));
    out.twilight_psi = converged_multiscattering_table(
        atm, transmittance_lut, twilight_psi_table_spec(), coarse, out.twilight_field,
        stage_context(ctx, 0.9, 1.0));
    out.twilight = psi_ms_source(atm, transmittance_lut, out.twilight_psi, spec.rays);
  }
  out.source.below_horizon = &out.twilight;
}

}  // namespace skybake

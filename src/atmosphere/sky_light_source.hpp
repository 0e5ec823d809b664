// The radiance source the sky-light products read (sky_irradiance,
// sky_environment; docs/decisions/sky-irradiance-source.md):
// - a viewer with the sun above its horizon: single scattering marched plus
//   the orders >= 2 of a converged 4D field, read directly (the field
//   source of sky_irradiance.hpp);
// - a viewer with the sun below it (twilight), by default the same from a
//   second field, fine along the sun (128 cosines down to 6 degrees past
//   the deepest sun), in r and in its density's directions, its ground
//   irradiance on 512 sun cosines. In twilight the light falls about 2x
//   per degree of sun; the daylight field's 16 sun cosines, and its lowest
//   at the shell's shadow, make deep twilight tens of times too bright.
//   Cheaper: the march with Psi_ms by view (converged_multiscattering.hpp,
//   a(nu) + b(mu_v)) tabulated from a coarse field, or the daylight field.
#pragma once

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "core/bake_context.hpp"
#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

// What viewers with the sun below their horizon read.
enum class TwilightSource {
  daylight_field,  // the daylight field (no second source)
  twilight_field,  // a second field read directly
  psi_ms_by_view,  // the march with Psi_ms by view from a coarse second field
};

struct SkyLightSourceSpec {
  ConvergedMultiscatteringSpec field;  // the daylight field
  TwilightSource twilight = TwilightSource::twilight_field;
  double deepest_sun_zenith_rad = 108.0 * kDeg;  // the twilight field's sun axis reaches past it
  SkyIrradianceSpec rays;  // psi_ms_by_view: the ground table's rays and steps, and sky_only
};

// The twilight field read directly: its tolerance is the daylight field's,
// its sun axis reaches 6 degrees past the deepest sun, the rest fixed
// (docs/decisions/sky-irradiance-source.md).
ConvergedMultiscatteringSpec twilight_field_spec(const ConvergedMultiscatteringSpec& daylight,
                                                 double deepest_sun_zenith_rad);
// psi_ms_by_view's field and table.
ConvergedMultiscatteringSpec psi_view_field_spec(const ConvergedMultiscatteringSpec& daylight);
MultiscatteringLutSpec twilight_psi_table_spec();

// The sources and what they own. `source` is what the bakers read; its
// below_horizon points at `twilight`, so the object is neither copied nor
// moved once made.
struct SkyLightSource {
  ConvergedField field;
  ConvergedField twilight_field;
  Texture twilight_psi;
  SkyRadianceSource twilight;
  SkyRadianceSource source;

  SkyLightSource() = default;
  SkyLightSource(const SkyLightSource&) = delete;
  SkyLightSource& operator=(const SkyLightSource&) = delete;
};

// Fills `out` for the atmosphere: the daylight field, then spec.twilight's
// field (and table). Progress: the daylight field the first 70% of ctx
// (all of it without a twilight source), the twilight source the rest.
void make_sky_light_source(SkyLightSource& out, const Atmosphere& atm,
                           const Texture& transmittance_lut, const SkyLightSourceSpec& spec,
                           const BakeContext& ctx);

}  // namespace skybake

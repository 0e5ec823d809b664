// The radiance source the sky-light products read (sky_irradiance,
// sky_environment; docs/decisions/sky-irradiance-source.md):
// - a viewer with the sun above its horizon: single scattering marched plus
//   the orders >= 2 of a converged 4D field, read directly (the field
//   source of sky_irradiance.hpp);
// - a viewer with the sun below it (twilight): the march with Psi_ms by
//   view (converged_multiscattering.hpp, a(nu) + b(mu_v)), tabulated from a
//   second field that is coarse in r, mu and nu and fine in mu_s, on a sun
//   axis that crowds its texels at the terminator and altitudes that crowd
//   near the ground. In twilight the light falls about 2x per degree of
//   sun; the daylight field's orders >= 2 read directly are read across 16
//   sun cosines and clamped below the field's lowest one, which makes deep
//   twilight tens of times too bright.
#pragma once

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyLightSourceSpec {
  ConvergedMultiscatteringSpec field;  // the daylight field
  bool twilight = true;                // false: the daylight field below the horizon too
  SkyIrradianceSpec rays;  // the twilight ground table's rays and steps, and sky_only
};

// The twilight source's field and table: its tolerance is the daylight
// field's, the rest fixed (docs/decisions/sky-irradiance-source.md).
ConvergedMultiscatteringSpec twilight_field_spec(const ConvergedMultiscatteringSpec& daylight);
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

// Fills `out` for the atmosphere: the daylight field, then (spec.twilight)
// the twilight field and table. Progress: the daylight field the first 70%
// of ctx, the twilight source the rest.
void make_sky_light_source(SkyLightSource& out, const Atmosphere& atm,
                           const Texture& transmittance_lut, const SkyLightSourceSpec& spec,
                           const BakeContext& ctx);

}  // namespace skybake

// Preset output objects (km, degrees) -> the atmosphere bakers' SI specs,
// converted here once; shared by the product table and the error estimates.
#pragma once

#include <string>
#include <vector>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/sky_environment.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "atmosphere/sky_light_source.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/skyview_multiple4d.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// The preset sections every atmosphere product's input hash covers.
inline const std::vector<std::string> kAtmosphereSections = {"planet", "atmosphere"};

TransmittanceLutSpec transmittance_spec(const OutputSpec& spec);
MultiscatteringLutSpec multiscattering_spec(const OutputSpec& spec);
// "model": "converged" (docs/reference.md "Converged Psi_ms"), and its 4D iteration.
bool multiscattering_is_converged(const OutputSpec& spec);
// "angular": "nu_zenith" (docs/reference.md "Psi_ms by view"), with
// "nu_slices" and "zenith_slices" (defaults below).
bool multiscattering_is_angular(const OutputSpec& spec);
constexpr int kDefaultNuSlices = 8, kDefaultZenithSlices = 8;
// The 4D iteration of either ("scattering_shape", "tolerance", "bands"),
// the estimator and the view-dependent source's slices.
ConvergedMultiscatteringSpec converged_multiscattering_spec(const OutputSpec& spec);
// Sky-view: "multiple_scattering": "scattering4d" (skyview_multiple4d.hpp).
bool skyview_uses_multiple4d(const OutputSpec& spec);
// Its 4D iteration: converged_multiscattering_spec, with the shape of
// orders_resolution.hpp where the Mie group shapes the multiple scattering
// and "scattering_shape" is the schema's default.
ConvergedMultiscatteringSpec skyview_multiple4d_spec(const OutputSpec& spec,
                                                     const Atmosphere& atm);
// The field of the sky-light products (sky_irradiance, sky_environment):
// converged_multiscattering_spec, with the default shape refined where the
// Mie group shapes the orders (orders_resolution.hpp sky_light_field_shape).
ConvergedMultiscatteringSpec sky_light_field_spec(const OutputSpec& spec, const Atmosphere& atm);
// Their whole source (atmosphere/sky_light_source.hpp): that field, and
// the "twilight_source" where some viewer has the sun below its horizon:
// the deepest sun is at deepest_sun_zenith_rad.
SkyLightSourceSpec sky_light_source_spec(const OutputSpec& spec, const Atmosphere& atm,
                                         double deepest_sun_zenith_rad);
// The radiance source of one sky-light bake, with what it owns: the march
// with the scene's multiscattering table ("radiance_source":
// "multiscattering_table") or make_sky_light_source's. Neither copied nor
// moved once made (the source points into it).
struct SkyLightHeld {
  SkyLightSource light;
  SkyRadianceSource psi_ms;
  const SkyRadianceSource& source() const { return psi_ms.transmittance ? psi_ms : light.source; }
};
// Makes it for the output `spec` (the products and the report alike): `rays`
// the march's rule, steps and sky_only; deepest_sun_zenith_rad as for
// sky_light_source_spec; `multiscattering` read with "multiscattering_table" only.
void make_sky_light_held(SkyLightHeld& out, const Atmosphere& atm, const OutputSpec& spec,
                         const Texture& transmittance, const Texture& multiscattering,
                         const SkyIrradianceSpec& rays, double deepest_sun_zenith_rad,
                         const BakeContext& ctx);
SkyviewLutSpec skyview_spec(const OutputSpec& spec);
AerialPerspectiveSpec aerial_perspective_spec(const OutputSpec& spec);
// Sky irradiance (sky_light_products.cpp): its spec, and whether its
// radiance comes from the multiscattering table ("radiance_source").
SkyIrradianceSpec sky_irradiance_spec(const OutputSpec& spec);
bool sky_irradiance_reads_multiscattering(const OutputSpec& spec);
SkyEnvironmentSpec sky_environment_spec(const OutputSpec& spec);
// Defined in bruneton_products.cpp.
BrunetonSpec bruneton_spec(const OutputSpec& spec);
Scattering3dSpec scattering3d_spec(const OutputSpec& spec);

}  // namespace skybake

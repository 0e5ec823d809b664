// The sky's irradiance for every normal, altitude and sun: per (sun zenith,
// altitude) texel the L2 spherical-harmonic coefficients of the radiance
// arriving at a viewer there, from the sky and, below the horizon, the lit
// ground (docs/reference.md "Sky irradiance (L2 SH)", docs/runtime.md "Sky
// irradiance"). E(n) is one dot product with the coefficients scaled by the
// clamped-cosine factors of Ramamoorthi & Hanrahan 2001 (sh_l2.hpp).
//
// Frame of a texel: z the local zenith, the sun in the x-z plane at
// (sin theta_s, 0, cos theta_s). The radiance is then symmetric about the
// x-z plane, so the three coefficients odd in y vanish and the six others
// are stored (kShSymmetricIndex). An engine turns a normal into this frame
// about the zenith by the sun's azimuth (lookup_sky_irradiance).
//
// Shape: width (sun zenith) x height (altitude), 6 layers (a 2D array),
// channels R, G, B. The coefficients L_k, k = kShSymmetricIndex[j] (Y_00,
// Y_10, Y_11, Y_20, Y_21, Y_22), in units of the sun's illuminance per
// steradian like the sky-view LUT, are stored as layer 0 = ln L_00 and
// layer j = L_k / L_00 (j = 1..5): the light falls by orders of magnitude
// across the terminator, about 2x per degree of sun in twilight, and
// bilinear reads of the logarithm follow that fall where reads of L_00
// itself overshoot by 100% and more between 3.5-degree columns; the
// ratios, the shape of the light, change slowly. Texel centres at the ends of both
// axes: theta_s = theta_max u, altitude = (Rt - Rb) v^2 (rows crowd near the
// ground, where the light changes fastest with height), u, v in [0, 1].
//
// Radiance: along the rays of a symmetric Gauss rule split at the viewer's
// horizon (sphere_rule.hpp), from one of two sources (SkyRadianceSource
// below; docs/decisions/sky-irradiance-source.md): single scattering
// marched plus the converged 4D field's orders >= 2 (the default), or the
// march with a multiple-scattering table's Psi_ms (Hillaire 2020 eq. 11);
// the texels with the sun below the horizon may read a source of their own
// (sky_light_source.hpp). Rays that meet the ground add its Lambertian
// response, attenuated along the ray. Each ray is marched once for every
// sun column of its row (sky_ray_suns.hpp). Reads: the transmittance
// table, and the field or the multiple-scattering table.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sh_l2.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyIrradianceSpec {
  int width = 32;   // sun zeniths
  int height = 16;  // altitudes
  double max_sun_zenith_rad = 108.0 * kDeg;  // the end of astronomical twilight
  bool sky_only = false;  // true: no light from the ground (the air in front of it stays)
  // Direction rule (symmetric_gauss_rule): Gauss nodes below and above the
  // horizon, midpoint azimuths on the half circle.
  int below = 6, above = 12, azimuths = 12;
  int steps = 40;  // march segments per ray
};

// One texel's radiance coefficients, all nine (the y-odd ones are 0).
using ShRadiance = std::array<glm::dvec3, kShL2Count>;

// The texel's axes.
double sky_irradiance_sun_zenith(const SkyIrradianceSpec& spec, int x);
double sky_irradiance_altitude(const Atmosphere& atm, const SkyIrradianceSpec& spec, int y);

// Where the radiance of a ray comes from (docs/decisions/sky-irradiance-source.md):
// - psi_ms: the march of sky_integrator.hpp with the multiple-scattering
//   table's Psi_ms (Hillaire 2020 eq. 11, either model of that table, by
//   view where it has view slices), the ground lit by the sun and by the
//   sky (ground_sky_irradiance);
// - field: single scattering marched, orders >= 2 read from the converged
//   4D field (skyview_multiple4d.hpp), the ground lit by the field's
//   irradiance of every order.
// With below_horizon set, a viewer whose sun is below its horizon (sun
// zenith > 90 degrees) reads that source instead (sky_light_source.hpp).
struct SkyRadianceSource {
  const Texture* transmittance = nullptr;
  const Texture* multiscattering = nullptr;  // psi_ms
  MultiscatteringMapping mapping{};          // psi_ms: that table's, parsed once (psi_ms_source)
  const ConvergedField* field = nullptr;     // field (takes precedence)
  std::vector<glm::dvec3> ground_sky;        // psi_ms: ground_sky_irradiance's table
  const SkyRadianceSource* below_horizon = nullptr;
};

// Twilight for a viewer: the sun below its horizon (sun zenith > 90 degrees).
inline bool sun_below_horizon(double sun_zenith_rad) { return sun_zenith_rad > 0.5 * kPi; }

// The source a viewer with the sun at this zenith angle reads.
const SkyRadianceSource& source_for_sun(const SkyRadianceSource& source, double sun_zenith_rad);

// The source's name in the products' metadata ("radiance_source"):
// "field" or "psi_ms".
std::string radiance_source_name(const SkyRadianceSource& source);

// Records the source in a product's metadata: "radiance_source", a field's
// "energy_out_over_in", and where viewers with the sun below their horizon
// read another source, "radiance_source_below_horizon" (and a field's
// shape and lowest sun cosine).
void set_sky_light_source_metadata(Metadata& m, const SkyRadianceSource& source);

// The sky's irradiance at the ground on a horizontal surface from the
// psi_ms march, tabulated on `nodes` sun cosines evenly spaced over [-1, 1]:
// the light the ground reflects besides the sun's.
std::vector<glm::dvec3> ground_sky_irradiance(const Atmosphere& atm,
                                              const Texture& transmittance_lut,
                                              const Texture& multiscattering_lut,
                                              const SkyIrradianceSpec& spec, int nodes);
constexpr int kGroundSkyNodes = 129;  // 1.4 degrees apart at the horizon

// A psi_ms source with its ground table.
SkyRadianceSource psi_ms_source(const Atmosphere& atm, const Texture& transmittance_lut,
                                const Texture& multiscattering_lut, const SkyIrradianceSpec& spec);

// The radiance arriving at `position` (planet-centred) from direction `dir`
// (unit, toward the source of the light) with the sun toward `sun_dir`:
// one ray of the source, the lit ground included unless sky_only.
glm::dvec3 sky_source_radiance(const Atmosphere& atm, const SkyRadianceSource& source,
                               bool sky_only, int steps, glm::dvec3 position, glm::dvec3 dir,
                               glm::dvec3 sun_dir);

// The coefficients at one altitude for each of several sun zeniths,
// integrated from scratch, each ray of the rule marched once for all of
// them (sky_ray_suns.hpp).
std::vector<ShRadiance> compute_sky_radiance_sh_suns(const Atmosphere& atm,
                                                     const SkyRadianceSource& source,
                                                     const SkyIrradianceSpec& spec,
                                                     double altitude_m,
                                                     const std::vector<double>& sun_zeniths_rad);

// The coefficients at one altitude and sun zenith, integrated from scratch.
ShRadiance compute_sky_radiance_sh(const Atmosphere& atm, const SkyRadianceSource& source,
                                   const SkyIrradianceSpec& spec, double altitude_m,
                                   double sun_zenith_rad);

// Every texel in parallel (independent of the thread count).
Texture bake_sky_irradiance(const Atmosphere& atm, const SkyRadianceSource& source,
                            const SkyIrradianceSpec& spec, const BakeContext& ctx);

// The stored form of a texel (the layout above) and back. L_00 is floored
// at kMinStoredL00 before its logarithm (a sky without light).
constexpr double kMinStoredL00 = 1e-30;
std::array<glm::dvec3, kShSymmetricCount> encode_sky_radiance_sh(const ShRadiance& sh);
ShRadiance decode_sky_radiance_sh(const std::array<glm::dvec3, kShSymmetricCount>& stored);

// Bilinear read of the stored form, decoded (clamp to edge), axes from the metadata.
ShRadiance lookup_sky_radiance_sh(const Texture& table, double altitude_m, double sun_zenith_rad);

// E(n) at an altitude for a unit normal n, a unit zenith `up` and a unit
// sun direction, in any frame: n is turned into the table's frame (x
// toward the sun's azimuth, z up) and decoded (sh_l2_irradiance).
glm::dvec3 lookup_sky_irradiance(const Texture& table, glm::dvec3 n, glm::dvec3 up,
                                 glm::dvec3 sun_dir, double altitude_m);

// The table's frame for (up, sun_dir): x, y, z rows; the sun's zenith angle.
struct SkyFrame {
  glm::dvec3 x, y, z;
  double sun_zenith_rad;
};
SkyFrame sky_frame(glm::dvec3 up, glm::dvec3 sun_dir);

// Cloud ambient, views of one texel's coefficients (docs/runtime.md "Cloud
// ambient"): the mean radiance over the sphere, L_00 Y_00 (the isotropic
// term), and the mean over the upper hemisphere of the L2 radiance,
// Y_00 L_00 + (Y_1 / 2) L_10 (the other five integrate to 0 there).
glm::dvec3 sh_mean_radiance(const ShRadiance& sh);
glm::dvec3 sh_mean_upper_radiance(const ShRadiance& sh);

}  // namespace skybake

// The 4D table's angular resolution where dust shapes the multiply
// scattered light (docs/report.md "Where the 4D table's error on Mars comes
// from", docs/decisions/mie-lobe-resolution.md). Where the Mie group
// scatters more than the Rayleigh group, the orders >= 2 carry Mie's
// forward lobe around the sun, some tens of degrees wide, which 8 nu slices
// (44 degrees apart next to nu = 1) and 32 sun texels interpolate coarsely;
// 16 slices and 64 sun texels resolve it (Mars: 7.3% -> 2.8% worst channel
// against the path tracer, in Bruneton's own storage, orders >= 2 / p_R).
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_orders.hpp"

namespace skybake {

// Vertical scattering optical depth of each group (scattering_lut.hpp's
// split), ground to top, per channel.
struct GroupScatteringDepths {
  glm::dvec3 rayleigh{0.0}, mie{0.0};
};
GroupScatteringDepths vertical_scattering_depths(const Atmosphere& atm);

// True where the Mie group's vertical scattering optical depth exceeds the
// Rayleigh group's in some channel (Mars; not Earth, nor the tiny planet).
bool mie_shapes_multiple_scattering(const Atmosphere& atm);

// The shape (r, mu, mu_s, nu) that resolves the lobe: 32 x 128 x 64 x 16.
constexpr int kMieLobeShape[4] = {32, 128, 64, 16};
// spec with that shape (the other settings kept).
BrunetonSpec with_mie_lobe_shape(BrunetonSpec spec);

// The in-memory field the sky-light products read (sky_irradiance,
// sky_environment), from the default field `spec`: where the Mie group
// shapes the orders, at least kSkyLightMieMu view zeniths and kSkyLightMieNu
// nu slices. On Mars the dust just above the horizon lights an upward
// surface: with 64 view zeniths the irradiance under an overhead sun was
// 4.3% RMS and 15% max off the path tracer, with 128 2.3% and 7.9% (targets
// 3% and 8%); 16 slices keep a low sun's aureole (ground, sun at 80 and 87
// degrees: 5.6 and 4.3% RMS, against 8.7 and 10.7% with 8). Finer r or mu_s
// change neither by more than 0.5 point (docs/decisions/sky-irradiance-source.md).
constexpr int kSkyLightMieMu = 128, kSkyLightMieNu = 16;
BrunetonSpec sky_light_field_shape(const Atmosphere& atm, BrunetonSpec spec);

}  // namespace skybake

// Hillaire's public demo (UnrealEngineSkyAtmosphere, Hillaire 2020) beyond
// his march (atmosphere/hillaire_demo_march.hpp), for the report section
// "Hillaire's runtime with skybake's tables" (report/hillaire_runtime.hpp):
// his sky-view read, and his own passes that make the tables each frame,
// so that his tables stay in the comparison.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/hillaire_demo_march.hpp"
#include "atmosphere/medium.hpp"
#include "core/texture.hpp"

namespace skybake {

// His sky-view read (SkyViewLutParamsToUv, 192 x 108) of layer `layer` for a
// viewer at `position` looking along `dir`.
glm::dvec3 demo_read_skyview(const Atmosphere& atm, const Texture& lut, int layer,
                             glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir);

// His passes, at his writers' texel positions:
// RenderTransmittanceLutPS: texel i at x = (i + 0.5) / n, 40 fixed samples.
Texture demo_transmittance_pass(const Atmosphere& atm, int width, int height);
// NewMultiScattCS: texel i at x = i / (n - 1), the altitude raised by 1 % of
// the shell, 8 x 8 directions, 20 fixed samples, the lit ground, isotropic
// phase; Psi_ms = L_2 / (1 - f_ms).
Texture demo_multiscattering_pass(const Atmosphere& atm, const Texture& transmittance, int size);
// SkyViewLutPS for one viewer altitude and sun: 192 x 108, texel i at
// x = i / (n - 1), `march` his render march (variable sample count).
Texture demo_skyview_pass(const Atmosphere& atm, const DemoTables& tables, double altitude_m,
                          glm::dvec3 sun_dir, const DemoMarch& march);

}  // namespace skybake

// The spectral reference of sky colour: the path tracer
// (reference/path_tracer.hpp) run at every group of three wavelengths of a
// spectral grid, its radiance integrated against the CIE 1931 functions and
// the sun's spectrum (core/spectral_grid.hpp's sun-weighted bins) into XYZ.
// Each group is three scalar transport problems, as in the RGB tracer; the
// groups use distinct random streams (seed + group).
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/spectral_medium.hpp"
#include "core/spectral_grid.hpp"
#include "reference/path_tracer.hpp"

namespace skybake {

struct SpectralRadianceEstimate {
  glm::dvec3 xyz{0.0};   // CIE XYZ, relative: the sun's Y at the top of the atmosphere is 1
  glm::dvec3 ci95{0.0};  // half-width of each component's 95% interval (groups independent)
};

// The sky's XYZ for viewer position_m looking along view_dir with the sun
// toward sun_dir, over `grid`'s wavelengths; `rgb` gives the profiles and
// phases, `medium` the coefficients, sun and albedo against wavelength.
SpectralRadianceEstimate trace_spectral_sky(const Atmosphere& rgb, const SpectralMedium& medium,
                                            const SpectralGrid& grid, glm::dvec3 position_m,
                                            glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                            const PathTracerSpec& spec);

}  // namespace skybake

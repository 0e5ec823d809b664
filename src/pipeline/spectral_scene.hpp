// A scene's spectral bake (docs/presets.md "Spectral skies"): how many
// wavelengths, the colour space and units of the tables, and the media
// against wavelength. Loaded with the scene (spectral_preset.cpp); absent
// from an RGB scene.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "atmosphere/spectral_medium.hpp"
#include "core/colour.hpp"
#include "core/spectral_grid.hpp"

namespace skybake {

enum class SpectralUnits {
  relative,     // the sun's luminance at the top of the atmosphere is 1
  radiometric,  // CIE-weighted W m^-2 sr^-1: luminance / 683 (Bruneton 2017)
  photometric,  // cd/m^2, the sun in lux
};

std::string spectral_units_name(SpectralUnits units);
std::string spectral_sampling_name(SpectralSampling sampling);

struct SpectralScene {
  int wavelengths = 15;  // as asked; the grid bakes 3 ceil(wavelengths / 3)
  ColourSpace colour_space = ColourSpace::rec709;
  SpectralUnits units = SpectralUnits::relative;
  SpectralSampling sampling = SpectralSampling::visible;
  SpectralMedium medium;

  SpectralGrid grid() const { return spectral_grid(wavelengths, sampling); }
  // The colour matrix of group g in the output's units (core/spectral_grid.hpp).
  glm::dmat3 group_matrix(const SpectralGrid& grid, size_t g) const;
  // The sun's colour at the top of the atmosphere in the output's units:
  // the sum of every group's matrix applied to 1.
  glm::dvec3 sun_colour() const;
};

}  // namespace skybake

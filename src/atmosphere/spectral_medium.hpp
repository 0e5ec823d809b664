// The atmosphere as a function of wavelength (docs/reference.md "Spectral
// skies"): per component a scattering and an absorption coefficient at
// density 1 for any wavelength, the sun's spectral irradiance and the
// ground's spectral albedo. The density profiles and phase functions stay
// those of the RGB Atmosphere; a spectral bake evaluates the medium at the
// three wavelengths of each group (atmosphere_at_wavelengths) and runs the
// RGB bakers on the result.
#pragma once

#include <map>
#include <string>

#include "atmosphere/medium.hpp"
#include "core/spectral_grid.hpp"

namespace skybake {

struct ComponentSpectrum {
  SpectrumFn scattering_per_m;  // empty: from the RGB coefficients (rgb_spectrum_at)
  SpectrumFn absorption_per_m;
};

struct SpectralMedium {
  std::map<std::string, ComponentSpectrum> components;  // by MediumComponent::name
  SpectrumFn sun_w_m2_nm;    // spectral irradiance at the top of the atmosphere
  SpectrumFn ground_albedo;  // empty: from the RGB albedo
};

// The RGB wavelengths of skybake's presets (Bruneton 2017 kLambdaR/G/B).
constexpr double kRedNm = 680.0, kGreenNm = 550.0, kBlueNm = 440.0;

// A spectrum through an RGB triple: linear in wavelength between 440, 550
// and 680 nm (blue, green, red), constant beyond.
double rgb_spectrum_at(const glm::dvec3& rgb, double nm);

// The Atmosphere at three wavelengths: each component's coefficients and
// the albedo at nm[0], nm[1], nm[2] in the R, G, B slots, and a sun of
// spectral irradiance 1 (the sun's spectrum enters through the group's
// colour matrix, core/spectral_grid.hpp).
Atmosphere atmosphere_at_wavelengths(const Atmosphere& rgb, const SpectralMedium& medium,
                                     const glm::dvec3& nm);

// int density dh from the ground to `height_m`, the column of a profile
// in metres at density 1 (trapezoids of 1 m).
double profile_column_m(const DensityProfile& profile, double height_m);

}  // namespace skybake

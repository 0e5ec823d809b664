#include "atmosphere/spectral_medium.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

double rgb_spectrum_at(const glm::dvec3& rgb, double nm) {
  if (nm <= kBlueNm) return rgb.b;
  if (nm <= kGreenNm) return rgb.b + (rgb.g - rgb.b) * (nm - kBlueNm) / (kGreenNm - kBlueNm);
  if (nm <= kRedNm) return rgb.g + (rgb.r - rgb.g) * (nm - kGreenNm) / (kRedNm - kGreenNm);
  return rgb.r;
}

namespace {

glm::dvec3 spectral_triple(const SpectrumFn& f, const glm::dvec3& rgb, const glm::dvec3& nm) {
  glm::dvec3 v;
  for (int k = 0; k < 3; ++k) v[k] = f ? f(nm[k]) : rgb_spectrum_at(rgb, nm[k]);
  return v;
}

}  // namespace

Atmosphere atmosphere_at_wavelengths(const Atmosphere& rgb, const SpectralMedium& medium,
                                     const glm::dvec3& nm) {
  Atmosphere a = rgb;
  a.sun_illuminance = glm::dvec3(1.0);
  a.ground_albedo = spectral_triple(medium.ground_albedo, rgb.ground_albedo, nm);
  for (MediumComponent& c : a.components) {
    auto it = medium.components.find(c.name);
    const ComponentSpectrum none;
    const ComponentSpectrum& s = it == medium.components.end() ? none : it->second;
    c.scattering_per_m = spectral_triple(s.scattering_per_m, c.scattering_per_m, nm);
    c.absorption_per_m = spectral_triple(s.absorption_per_m, c.absorption_per_m, nm);
  }
  return a;
}

double profile_column_m(const DensityProfile& profile, double height_m) {
  if (profile.layers.empty() || !(height_m > 0.0)) return 0.0;
  const long steps = std::max(1L, long(std::ceil(height_m)));
  const double h = height_m / double(steps);
  double sum = 0.5 * (density_at(profile, 0.0) + density_at(profile, height_m));
  for (long i = 1; i < steps; ++i) sum += density_at(profile, i * h);
  return sum * h;
}

}  // namespace skybake

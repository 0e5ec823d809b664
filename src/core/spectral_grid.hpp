// The wavelengths of a spectral bake and their conversion to colour
// (Bruneton 2017 "luminance_from_radiance", with sun-weighted bins;
// docs/decisions/spectral-tables.md). N wavelengths become ceil(N / 3)
// groups of three: the midpoints l_k of 3 ceil(N / 3) equal bins B_k over
// [360, 830] nm. A quantity R known at a group's three wavelengths, relative
// to the sun (a radiance for a sun of spectral irradiance 1), adds
//   RGB += M R,  column k of M = rgb_from_xyz int_{B_k} xyz_bar(l) S(l) dl
// to its colour, S the sun's spectral irradiance: the integral of
// R(l) S(l) xyz_bar(l) with R constant over each bin. The sun's own jagged
// spectrum is integrated exactly; only the atmosphere's smooth response is
// sampled.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace skybake {

struct SpectralGrid {
  std::vector<glm::dvec3> groups;  // the three wavelengths of each group, nm
  double step_nm = 0.0;            // bin width
  int wavelength_count() const { return 3 * int(groups.size()); }
};

using SpectrumFn = std::function<double(double)>;  // value at a wavelength in nm

// ceil(wavelengths / 3) groups over [360, 830] nm; wavelengths >= 1.
SpectralGrid spectral_grid(int wavelengths);

// M of one group (above): RGB, or XYZ with rgb_from_xyz the identity.
glm::dmat3 group_colour_matrix(const SpectralGrid& grid, size_t group, const SpectrumFn& sun,
                               const glm::dmat3& rgb_from_xyz);

// XYZ of R(l) S(l) by the grid (R sampled at the wavelengths, above).
glm::dvec3 grid_xyz(const SpectralGrid& grid, const SpectrumFn& response, const SpectrumFn& sun);

// XYZ of a spectral density by the midpoint rule at `step_nm` over the CIE
// table's whole range (the fine reference for grid_xyz).
glm::dvec3 spectrum_xyz(const SpectrumFn& spectrum, double step_nm = 1.0);

}  // namespace skybake

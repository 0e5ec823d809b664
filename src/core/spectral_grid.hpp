// The wavelengths of a spectral bake and their conversion to colour
// (Bruneton 2017 "luminance_from_radiance", with sun-weighted bins;
// docs/decisions/spectral-tables.md). N wavelengths become ceil(N / 3)
// groups of three: the midpoints l_k of 3 ceil(N / 3) equal bins B_k over
// the sampled range, [395, 695] nm by default, the first and last bins
// reaching on to 360 and 830 nm. A quantity R known at a group's three wavelengths,
// relative to the sun (a radiance for a sun of spectral irradiance 1), adds
//   RGB += M R,  column k of M = rgb_from_xyz int_{B_k} xyz_bar(l) S(l) dl
// to its colour, S the sun's spectral irradiance: the integral of
// R(l) S(l) xyz_bar(l) with R constant over each bin. The sun's own jagged
// spectrum is integrated exactly over the whole CIE range; only the
// atmosphere's smooth response is sampled, and only where the eye weighs it
// (outside the sampled range lies under 0.5% of each colour-matching
// function's integral).
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace skybake {

// The range the wavelengths sample by default, nm: chosen by measurement
// against a 120-wavelength uniform bake (docs/decisions/spectral-tables.md).
constexpr double kSampledMinNm = 395.0;
constexpr double kSampledMaxNm = 695.0;

enum class SpectralSampling {
  visible,  // equal bins over [395, 695] nm, the end bins reaching 360 and 830
  uniform,  // equal bins over [360, 830] nm (Bruneton 2017): converges to the
            // whole integral as N grows, for references
};

struct SpectralGrid {
  std::vector<glm::dvec3> groups;  // the three wavelengths of each group, nm
  double step_nm = 0.0;            // bin width inside the sampled range
  std::vector<double> edges;       // 3 groups + 1 bin edges, nm, 360 to 830
  int wavelength_count() const { return 3 * int(groups.size()); }
  // Bin edges of wavelength k of `group`.
  glm::dvec2 bin(size_t group, int k) const;
};

using SpectrumFn = std::function<double(double)>;  // value at a wavelength in nm

// ceil(wavelengths / 3) groups over the sampled range; wavelengths >= 1.
SpectralGrid spectral_grid(int wavelengths,
                           SpectralSampling sampling = SpectralSampling::visible);

// M of one group (above): RGB, or XYZ with rgb_from_xyz the identity.
glm::dmat3 group_colour_matrix(const SpectralGrid& grid, size_t group, const SpectrumFn& sun,
                               const glm::dmat3& rgb_from_xyz);

// XYZ of R(l) S(l) by the grid (R sampled at the wavelengths, above).
glm::dvec3 grid_xyz(const SpectralGrid& grid, const SpectrumFn& response, const SpectrumFn& sun);

// XYZ of a spectral density by the midpoint rule at `step_nm` over the CIE
// table's whole range (the fine reference for grid_xyz).
glm::dvec3 spectrum_xyz(const SpectrumFn& spectrum, double step_nm = 1.0);

}  // namespace skybake

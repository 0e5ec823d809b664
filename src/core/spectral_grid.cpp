#include "core/spectral_grid.hpp"

#include <algorithm>
#include <cmath>

#include "core/spectral_data.hpp"

namespace skybake {

namespace {

// Midpoints per bin, at most 0.25 nm apart: the tables are linear between
// their 5 and 10 nm samples.
constexpr double kBinStepNm = 0.25;

glm::dvec3 spectral_bin_xyz(double lo_nm, double hi_nm, const SpectrumFn& sun) {
  const int steps = std::max(1, int(std::ceil((hi_nm - lo_nm) / kBinStepNm)));
  const double h = (hi_nm - lo_nm) / steps;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < steps; ++i) {
    const double nm = lo_nm + (i + 0.5) * h;
    sum += cie1931_xyz_bar(nm) * sun(nm);
  }
  return sum * h;
}

}  // namespace

SpectralGrid spectral_grid(int wavelengths, SpectralSampling sampling) {
  const bool visible = sampling == SpectralSampling::visible;
  const double lo = visible ? kSampledMinNm : kSpectrumMinNm;
  const double hi = visible ? kSampledMaxNm : kSpectrumMaxNm;
  const int n = 3 * std::max(1, (wavelengths + 2) / 3);
  SpectralGrid g;
  g.step_nm = (hi - lo) / n;
  for (int i = 0; i <= n; ++i) g.edges.push_back(lo + i * g.step_nm);
  g.edges.front() = kSpectrumMinNm;
  g.edges.back() = kSpectrumMaxNm;
  for (int i = 0; i < n; i += 3)
    g.groups.push_back(lo + (double(i) + glm::dvec3(0.5, 1.5, 2.5)) * g.step_nm);
  return g;
}

glm::dvec2 SpectralGrid::bin(size_t group, int k) const {
  return {edges.at(3 * group + k), edges.at(3 * group + k + 1)};
}

glm::dmat3 group_colour_matrix(const SpectralGrid& grid, size_t group, const SpectrumFn& sun,
                               const glm::dmat3& rgb_from_xyz) {
  glm::dmat3 xyz(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec2 b = grid.bin(group, k);
    xyz[k] = spectral_bin_xyz(b.x, b.y, sun);
  }
  return rgb_from_xyz * xyz;
}

glm::dvec3 grid_xyz(const SpectralGrid& grid, const SpectrumFn& response, const SpectrumFn& sun) {
  glm::dvec3 xyz(0.0);
  for (size_t g = 0; g < grid.groups.size(); ++g) {
    const glm::dvec3& nm = grid.groups[g];
    const glm::dvec3 r(response(nm[0]), response(nm[1]), response(nm[2]));
    xyz += group_colour_matrix(grid, g, sun, glm::dmat3(1.0)) * r;
  }
  return xyz;
}

glm::dvec3 spectrum_xyz(const SpectrumFn& spectrum, double step_nm) {
  const int n = int(std::lround((kSpectrumMaxNm - kSpectrumMinNm) / step_nm));
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < n; ++i) {
    const double nm = kSpectrumMinNm + (i + 0.5) * step_nm;
    xyz += cie1931_xyz_bar(nm) * spectrum(nm);
  }
  return xyz * step_nm;
}

}  // namespace skybake

#include "pipeline/spectral_scene.hpp"

#include "core/spectral_data.hpp"

namespace skybake {

std::string spectral_sampling_name(SpectralSampling sampling) {
  return sampling == SpectralSampling::uniform ? "uniform" : "visible";
}

std::string spectral_units_name(SpectralUnits units) {
  switch (units) {
    case SpectralUnits::relative: return "relative";
    case SpectralUnits::radiometric: return "radiometric";
    case SpectralUnits::photometric: return "photometric";
  }
  return "relative";
}

namespace {

// The factor on CIE-weighted watts of each unit system.
double spectral_unit_scale(const SpectralScene& s) {
  if (s.units == SpectralUnits::photometric) return kMaxLuminousEfficacy;
  if (s.units == SpectralUnits::radiometric) return 1.0;
  // relative: the sun's Y is 1 (its XYZ is the same for every grid, up to
  // the bins' quadrature; the grid's own sum makes it exactly 1).
  const SpectralGrid grid = s.grid();
  const glm::dvec3 xyz = grid_xyz(grid, [](double) { return 1.0; }, s.medium.sun_w_m2_nm);
  return 1.0 / xyz.y;
}

}  // namespace

glm::dmat3 SpectralScene::group_matrix(const SpectralGrid& grid, size_t g) const {
  const glm::dmat3 to_rgb = rgb_from_xyz(chromaticities_of(colour_space));
  return group_colour_matrix(grid, g, medium.sun_w_m2_nm, to_rgb) * spectral_unit_scale(*this);
}

glm::dvec3 SpectralScene::sun_colour() const {
  const SpectralGrid g = grid();
  glm::dvec3 c(0.0);
  for (size_t i = 0; i < g.groups.size(); ++i) c += group_matrix(g, i) * glm::dvec3(1.0);
  return c;
}

}  // namespace skybake

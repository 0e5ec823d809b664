#include "reference/spectral_path_tracer.hpp"

#include <cmath>

namespace skybake {

SpectralRadianceEstimate trace_spectral_sky(const Atmosphere& rgb, const SpectralMedium& medium,
                                            const SpectralGrid& grid, glm::dvec3 position_m,
                                            glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                            const PathTracerSpec& spec) {
  glm::dvec3 xyz(0.0), variance(0.0);
  double sun_y = 0.0;
  for (size_t g = 0; g < grid.groups.size(); ++g) {
    const Atmosphere atm = atmosphere_at_wavelengths(rgb, medium, grid.groups[g]);
    const glm::dmat3 m = group_colour_matrix(grid, g, medium.sun_w_m2_nm, glm::dmat3(1.0));
    PathTracerSpec s = spec;
    s.seed = spec.seed + g;
    const RadianceEstimate e = trace_sky_radiance(atm, position_m, view_dir, sun_dir, s);
    xyz += m * e.mean;
    // Independent channels and groups: the variances add through M^2.
    const glm::dvec3 se = e.ci95 / 1.96;
    for (int row = 0; row < 3; ++row)
      for (int k = 0; k < 3; ++k) variance[row] += m[k][row] * m[k][row] * se[k] * se[k];
    sun_y += (m * glm::dvec3(1.0)).y;
  }
  SpectralRadianceEstimate out;
  out.xyz = xyz / sun_y;
  for (int i = 0; i < 3; ++i) out.ci95[i] = 1.96 * std::sqrt(variance[i]) / sun_y;
  return out;
}

}  // namespace skybake

// The texels of a sky-view row half (skyview_lut.cpp): the in-scattered
// luminance of Hillaire 2020 eq. 11 (skyview_row_march.hpp's
// skyview_texel_luminance) of n texels of one row, the same bits as one
// texel at a time.
#pragma once

#include "atmosphere/skyview_row_march.hpp"

namespace skybake {

// skyview_texel_luminance of n texels of the row, texel k at (cos_phi[k],
// nu[k]), into out[k]: the same bits, several texels at a time over lanes
// (tests/atmosphere/kernels_test.cpp).
void skyview_row_luminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                           const Texture& transmittance_lut, const Texture& multiscattering_lut,
                           const double* cos_phi, const double* nu, int n, double cos_theta_s,
                           double sin_theta_s, glm::dvec3* out);

}  // namespace skybake

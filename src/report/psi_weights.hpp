// The report's sky views as a linear function of a multiple-scattering
// table (docs/decisions/converged-psi-ms.md). Hillaire's runtime adds E sigma_s Psi_ms(r, mu_s) to each
// march step of the sky-view bake, reading Psi_ms bilinearly, and the
// report reads the layer bilinearly too: every rendered view is
//   L_v,c = single_v,c + sum_k weights_v,k,c x_k,c
// with x_k,c texel k's value in channel c (channels do not mix). The
// weights are found by rendering the views with unit tables through the
// report's own rendering (render_sky_views), so they are exactly what the
// report measures, float32 layers included. A table by view
// (docs/reference.md "Psi_ms by view") is a volume: its texels are every
// slice's, k = (z * height + y) * width + x (slice 0, which the views do
// not read, weighs nothing).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/texture.hpp"
#include "report/sky_radiance.hpp"

namespace skybake {

struct PsiWeights {
  int width = 0, height = 0;        // the table's texels
  int depth = 1;                    // its slices (a table by view)
  size_t views = 0;                 // sun elevations x camera.dirs, sun outer (the report's order)
  std::vector<glm::dvec3> single;   // per view: the rendering with Psi_ms = 0
  std::vector<glm::dvec3> weights;  // [view * texels + texel], per channel

  size_t texels() const { return size_t(width) * size_t(height) * size_t(depth); }
  glm::dvec3 weight(size_t view, int x, int y, int z = 0) const {
    return weights[view * texels() + (size_t(z) * size_t(height) + size_t(y)) * size_t(width) +
                   size_t(x)];
  }
};

// The weights of every texel of a table shaped like `layout` (its size and
// its mapping metadata; its values are not read) in the views of `camera`
// under each sun elevation.
PsiWeights sky_view_psi_weights(const Atmosphere& atm, const Texture& transmittance,
                                const Texture& layout, const SkyRadianceCamera& camera,
                                const std::vector<double>& sun_elevations_deg);

// single + weights . table: the views rendered from `table` (same layout).
std::vector<glm::dvec3> apply_psi_weights(const PsiWeights& w, const Texture& table);

}  // namespace skybake

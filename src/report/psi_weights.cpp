#include "report/psi_weights.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace skybake {

PsiWeights sky_view_psi_weights(const Atmosphere& atm, const Texture& transmittance,
                                const Texture& layout, const SkyRadianceCamera& camera,
                                const std::vector<double>& sun_elevations_deg) {
  PsiWeights w;
  w.width = layout.width;
  w.height = layout.height;
  w.depth = layout.depth;
  const size_t texels = w.texels(), per_sun = camera.dirs.size();
  w.views = sun_elevations_deg.size() * per_sun;
  w.weights.assign(w.views * texels, glm::dvec3(0.0));
  Texture zero = layout;
  std::fill(zero.data.begin(), zero.data.end(), 0.0f);
  for (size_t s = 0; s < sun_elevations_deg.size(); ++s)
    for (const glm::dvec3& l :
         render_sky_views(atm, transmittance, zero, camera, sun_elevations_deg[s]))
      w.single.push_back(l);
  // One unit table per texel (1 in every channel: channels do not mix); the
  // rendering is linear in the table, so the weight is the difference. A unit
  // of 1 is far above any Psi_ms (units of the sun's illuminance), so the
  // float32 layer's rounding of the single part stays negligible beside it.
  tbb::parallel_for(size_t(0), texels, [&](size_t k) {
    Texture unit = zero;
    const size_t channels = unit.channels.size();
    for (size_t c = 0; c < std::min<size_t>(channels, 3); ++c) unit.data[k * channels + c] = 1.0f;
    for (size_t s = 0; s < sun_elevations_deg.size(); ++s) {
      const std::vector<glm::dvec3> l =
          render_sky_views(atm, transmittance, unit, camera, sun_elevations_deg[s]);
      for (size_t v = 0; v < per_sun; ++v) {
        const size_t view = s * per_sun + v;
        w.weights[view * texels + k] = l[v] - w.single[view];
      }
    }
  });
  return w;
}

std::vector<glm::dvec3> apply_psi_weights(const PsiWeights& w, const Texture& table) {
  std::vector<glm::dvec3> out = w.single;
  const size_t texels = w.texels(), channels = table.channels.size();
  for (size_t v = 0; v < w.views; ++v)
    for (size_t k = 0; k < texels; ++k)
      for (int c = 0; c < 3; ++c)
        out[v][c] += w.weights[v * texels + k][c] * double(table.data[k * channels + size_t(c)]);
  return out;
}

}  // namespace skybake

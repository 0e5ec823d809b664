// Filtered reads of a Texture, the way a GPU samples the LUTs we bake:
// texel centres at (i + 0.5) / n, bilinear, clamp to edge (or wrap in u).
#pragma once

#include <glm/glm.hpp>

#include "core/texture.hpp"

namespace skybake {

// Bilinear filtering of slice z of `layer` at texture coordinates (u, v),
// clamp to edge in v, wrap or clamp in u. Returns the first min(4, channels)
// channels (the rest 0).
glm::dvec4 sample_bilinear(const Texture& tex, double u, double v, int z, int layer, bool wrap_u);

}  // namespace skybake

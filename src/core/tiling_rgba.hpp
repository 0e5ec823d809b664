// compute_tiling_profiles (core/tiling_profiles.hpp) for textures of four
// channels, the cloud shape volume's case: the sums of every channel in one
// walk over the texture (kernels/tiling_rgba.hpp), the same terms in the
// same order as the definition, so every mean is the same double to the
// last bit, on every SIMD target.
#pragma once

#include <vector>

#include "core/tiling_profiles.hpp"

namespace skybake {

// The profiles of channels 0..3 of a four-channel texture along `axis`.
std::vector<TilingProfiles> compute_tiling_profiles_rgba(const Texture& t, int layer, int axis);

}  // namespace skybake

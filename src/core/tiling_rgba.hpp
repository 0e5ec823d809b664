// compute_tiling_profiles (core/tiling_profiles.hpp) for textures of four
// channels, the cloud shape volume's case: one texel's four channels sit in
// the four lanes of a vector, so a line of texels is walked once for every
// channel, read straight from the texture (no plane of doubles, no padded
// copy per channel). Each lane adds the same terms in the same order as the
// definition (lines in plane order, faces and lags in order along a line),
// so every mean is the same double to the last bit, with AVX2 on or off.
#pragma once

#include <vector>

#include "core/tiling_profiles.hpp"

namespace skybake {

// The profiles of channels 0..3 of a four-channel texture along `axis`.
std::vector<TilingProfiles> compute_tiling_profiles_rgba(const Texture& t, int layer, int axis);

}  // namespace skybake

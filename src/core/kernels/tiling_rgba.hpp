// The sums behind the tiling measure's profiles (core/tiling_profiles.hpp)
// of a four-channel texture, the cloud shape volume's case, over lanes
// (Highway): one texel's four channels in the lanes (one vector of four
// doubles, or two of two, or four of one, as the target holds), so a line of
// texels is walked once for every channel, read straight from the texture.
// Each lane adds the same terms in the same order as the definition (lines
// in plane order, faces and lags in order along a line), so every sum is
// the same double on every target (tests/core/tiling_profiles_test.cpp).
#pragma once

#include <vector>

#include "core/texture.hpp"

namespace skybake {

// A texel's four channels (doubles), the lanes of one texel.
struct alignas(32) TexelChannels {
  double c[4];
};

// Per face f along the axis, summed over every line: the jump |d_f|, its
// busier side's half pair, the turn k_f and its busier side's half pair
// (core/tiling.hpp); per channel, the far jumps summed over lines, lags and
// texels.
struct TilingRgbaSums {
  std::vector<TexelChannels> jump, jump_side, turn, turn_side;
  long double far[4] = {0.0L, 0.0L, 0.0L, 0.0L};
};

// The sums of layer `layer` of `t` (four channels) along `axis`, far jumps
// at the lags `lags`.
TilingRgbaSums tiling_rgba_sums(const Texture& t, int layer, int axis,
                                const std::vector<int>& lags);

}  // namespace skybake

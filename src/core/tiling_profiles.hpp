// The per-face means that core/tiling.cpp judges a seam from (the statistic
// is written down in core/tiling.hpp): for one layer, channel and axis of a
// texture, over every line of texels along the axis.
//
// The lines of one plane are read together, texel i of every line side by
// side (a row of the plane in memory order), so the inner loops run over
// contiguous memory and vectorize; a line is padded with the texels it wraps
// to instead of wrapping each index. Every sum adds the same terms in the
// same order as the line-at-a-time definition (lines in plane order, u
// fastest; faces and lags in order along a line), so the means are the same
// doubles to the last bit whatever the memory order.
#pragma once

#include <vector>

#include "core/texture.hpp"

namespace skybake {

// Per face f (texels f, f + 1 mod n), means over every line: the jump
// |d_f| and the slope turn |d_{f+1} - d_{f-1}|, each with its busier side
// (per line, the larger of the means over two faces before and two faces
// after f: f - 2, f - 1 | f + 1, f + 2 for jumps, f - 3, f - 2 | f + 2,
// f + 3 for turns, whose f +- 1 share a difference with f); and the mean far
// jump |v(i + lag) - v(i)| over lags n/2, n/3, n/4, n/5 (distinct, >= 2).
struct TilingProfiles {
  std::vector<double> jump, jump_side, turn, turn_side;
  double far = 0.0;
};

// One per channel of the layer, along `axis` (0, 1, 2 for x, y, z; at
// least 2 texels). Each texel is read once for all channels.
std::vector<TilingProfiles> compute_tiling_profiles(const Texture& t, int layer, int axis);

}  // namespace skybake

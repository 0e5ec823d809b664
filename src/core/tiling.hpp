// Tileability of a texture, measured the way `skybake check-tiling` reports
// it: for each axis and channel, the largest jump between neighbours across
// the wrapped face (last texel -> first texel) against the largest jump
// between interior neighbours along the same axis. A tiling texture's wrapped
// face is just one more face between neighbours, so the ratio stays near or
// below 1; a texture that does not tile jumps by several times more there.
// Layers of an array are measured independently and the worst is kept.
#pragma once

#include <string>
#include <vector>

#include "core/texture.hpp"

namespace skybake {

struct AxisTiling {
  char axis = 'x';         // 'x', 'y' or 'z'
  std::string channel;
  double seam_jump = 0.0;      // largest |v(n-1) - v(0)| across the wrapped face
  double interior_jump = 0.0;  // largest |v(i+1) - v(i)| inside
  // seam / interior; 0 when both are 0 (constant), +inf when only the seam jumps.
  double ratio = 0.0;
  bool tiles = true;
};

struct TilingReport {
  std::vector<AxisTiling> axes;  // every axis with more than one texel, every channel
  bool tiles = true;
  double worst_ratio = 0.0;
};

// `tolerance`: a face passes when ratio <= 1 + tolerance.
TilingReport measure_tiling(const Texture& tex, double tolerance);

}  // namespace skybake

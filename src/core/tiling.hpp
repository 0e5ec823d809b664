// Tileability of a texture, measured the way `skybake check-tiling` reports
// it (README "check-tiling", docs/clouds.md "Checking that a texture tiles").
//
// A texture tiles when its wrapped face (last texel -> first texel of an
// axis) is just one more face between neighbours. Each face f of an axis of
// n texels (between texels f and f + 1, face n - 1 being the seam) gets two
// scores from the lines of texels along the axis (every row, column or
// pillar of a layer), with d_f = v(f + 1) - v(f):
//   values  V_f = mean|d_f| / mean of max(|d_{f-2}| + |d_{f-1}|, |d_{f+1}| + |d_{f+2}|) / 2
//           the face's jump against the jumps beside it, on the busier side;
//   slopes  S_f = mean t_f / mean of max(t_{f-3} + t_{f-2}, t_{f+2} + t_{f+3}) / 2,
//           t_f = |d_{f+1} - d_{f-1}|: how sharply the slope turns there.
// Means run over the lines, so a score is one number per face; dividing by
// the neighbours cancels how busy that part of the texture is (a streak
// raises a face and its neighbours alike), and taking the busier side keeps
// the edge of a flat region (a clamped cloud, zero on one side) from
// looking like a seam. The seam's score is compared with the distribution of
// the same score over the interior faces (those whose stencil does not hold
// both texels n - 1 and 0): with m their median and q their 90th
// percentile, the seam fails above
//   values  m + max(tolerance m, 4 (q - m))
//   slopes  m + max(1.5 m, 4 (q - m))
// (slopes get more room: Worley and ridged noise turn sharply anywhere).
//
// A seam can only show where texels far apart differ more than neighbours
// do. The contrast is the mean |v(i + lag) - v(i)| over lags n/2, n/3, n/4
// and n/5 over the median interior mean|d_f|: a seam joining unrelated texels
// scores about contrast x m. When that does not exceed the values limit
// (white noise, or a mip level coarser than the features) no seam could be
// told from the interior: at level 0 that is the verdict "cannot tell"
// (check-tiling exits 1) unless another channel along the same axis is
// judged (a crop or a shift cuts every channel at once: the rough channel is
// then not judged), at smaller mip levels the level is not judged.
// Level 0 axes shorter than 16 texels cannot tell either; mip levels are
// judged from 32 texels along the axis.
#pragma once

#include <string>
#include <vector>

#include "core/texture.hpp"

namespace skybake {

enum class TilingVerdict {
  tiles,        // the seam is like the interior faces (or the axis is constant)
  seam,         // the seam stands out: the texture does not tile
  cannot_tell,  // level 0 too small or too rough for a seam to show, on every channel
  not_judged,   // a smaller mip level too small or too rough: not counted
};

// "tiles", "seam", "cannot_tell", "not_judged".
const char* tiling_verdict_name(TilingVerdict v);

// One score (values or slopes) of the seam against the interior faces.
struct SeamScore {
  double seam = 0.0;    // the seam face's score
  double median = 0.0;  // of the interior faces
  double q90 = 0.0;     // 90th percentile of the interior faces
  double limit = 0.0;   // the seam fails above it
};

struct AxisTiling {
  int level = 0;  // mip level
  int layer = 0;  // array layer
  char axis = 'x';  // 'x', 'y' or 'z'
  std::string channel;
  int texels = 0;  // along the axis
  TilingVerdict verdict = TilingVerdict::tiles;
  std::string reason;  // why not judged, cannot tell or constant; "" otherwise
  SeamScore values, slopes;
  double contrast = 0.0;  // far jumps over neighbour jumps (see above)
  // values.seam / values.limit and slopes.seam / slopes.limit, the larger;
  // above 1 fails. 0 when not judged or constant.
  double ratio = 0.0;
  bool tiles = true;  // verdict is tiles or not_judged
};

struct TilingReport {
  // Every level, layer, axis with more than one texel and channel, in that order.
  std::vector<AxisTiling> axes;
  TilingVerdict verdict = TilingVerdict::tiles;  // seam if any, else cannot_tell if any
  bool tiles = true;                             // verdict == tiles
  double worst_ratio = 0.0;                      // largest AxisTiling::ratio
};

// Measures one texture (level 0, every layer). `tolerance`: the values
// margin above (0.25 in check-tiling).
TilingReport measure_tiling(const Texture& tex, double tolerance);

// Measures a mip chain: level 0 and the levels below it (level 1 first).
TilingReport measure_tiling(const Texture& level0, const std::vector<Texture>& lower_levels,
                            double tolerance);

}  // namespace skybake

#include "core/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace skybake {

namespace {

// Largest seam and interior jumps of one channel along one axis, over all
// rows of that axis in every layer.
AxisTiling measure_axis(const Texture& t, int channel, int axis) {
  const int n[3] = {t.width, t.height, t.depth};
  AxisTiling a;
  a.axis = char('x' + axis);
  a.channel = t.channels[channel];
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  for (int layer = 0; layer < t.layers; ++layer)
    for (int v = 0; v < n[v_axis]; ++v)
      for (int u = 0; u < n[u_axis]; ++u) {
        auto value = [&](int i) {
          int c[3];
          c[axis] = i;
          c[u_axis] = u;
          c[v_axis] = v;
          return double(t.at(c[0], c[1], c[2], layer, channel));
        };
        for (int i = 0; i + 1 < len; ++i)
          a.interior_jump = std::max(a.interior_jump, std::abs(value(i + 1) - value(i)));
        a.seam_jump = std::max(a.seam_jump, std::abs(value(0) - value(len - 1)));
      }
  if (a.interior_jump > 0.0) {
    a.ratio = a.seam_jump / a.interior_jump;
  } else {
    a.ratio = a.seam_jump > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  return a;
}

}  // namespace

TilingReport measure_tiling(const Texture& tex, double tolerance) {
  TilingReport report;
  const int n[3] = {tex.width, tex.height, tex.depth};
  for (int axis = 0; axis < 3; ++axis) {
    if (n[axis] < 2) continue;
    for (int c = 0; c < tex.channel_count(); ++c) {
      AxisTiling a = measure_axis(tex, c, axis);
      a.tiles = a.ratio <= 1.0 + tolerance;
      report.tiles = report.tiles && a.tiles;
      report.worst_ratio = std::max(report.worst_ratio, a.ratio);
      report.axes.push_back(a);
    }
  }
  return report;
}

}  // namespace skybake

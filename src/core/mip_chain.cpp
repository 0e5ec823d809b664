// Area-weighted box mip chains (see mip_chain.hpp for the filter and why it
// preserves the mean and the tiling at every size).
#include "core/mip_chain.hpp"

#include <algorithm>
#include <cassert>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/math.hpp"

namespace skybake {
namespace {

struct Tap {
  int index;      // input texel along the axis
  double weight;  // overlap / footprint width; the taps of one output sum to 1
};

// Taps for every output texel of an axis going from n_in to n_out texels.
// Positions are scaled by n_in * n_out so every boundary is an integer:
// input texel i spans [i * n_out, (i+1) * n_out), output j spans
// [j * n_in, (j+1) * n_in), and the weights are exact rationals.
std::vector<std::vector<Tap>> axis_taps(int n_in, int n_out, MipEdge edge) {
  std::vector<std::vector<Tap>> taps(n_out);
  for (int j = 0; j < n_out; ++j) {
    const long long lo = (long long)j * n_in, hi = (long long)(j + 1) * n_in;
    for (long long i = lo / n_out; i * n_out < hi; ++i) {
      const long long overlap = std::min(hi, (i + 1) * n_out) - std::max(lo, i * n_out);
      if (overlap <= 0) continue;
      const int at =
          edge == MipEdge::wrap ? wrap_index(int(i), n_in) : std::clamp(int(i), 0, n_in - 1);
      taps[j].push_back({at, double(overlap) / double(n_in)});
    }
  }
  return taps;
}

// Output row (y, z, layer) filtered along x: each texel's taps in order.
void reduce_row_along_x(const Texture& in, int y, int z, int layer,
                        const std::vector<std::vector<Tap>>& taps, std::vector<double>& sum) {
  const size_t nc = in.channels.size();
  const float* row = in.texel(0, y, z, layer);
  std::fill(sum.begin(), sum.end(), 0.0);
  for (size_t x = 0; x < taps.size(); ++x) {
    double* acc = &sum[x * nc];
    for (const Tap& tap : taps[x]) {
      const float* src = row + size_t(tap.index) * nc;
      for (size_t c = 0; c < nc; ++c) acc[c] += tap.weight * src[c];
    }
  }
}

// Output row (y, z, layer) filtered along y or z: every texel of the row has
// the same taps, input rows added whole, in tap order.
void reduce_row_across(const Texture& in, int axis, int y, int z, int layer,
                       const std::vector<std::vector<Tap>>& taps, std::vector<double>& sum) {
  std::fill(sum.begin(), sum.end(), 0.0);
  for (const Tap& tap : taps[axis == 1 ? y : z]) {
    const float* src =
        axis == 1 ? in.texel(0, tap.index, z, layer) : in.texel(0, y, tap.index, layer);
    const double w = tap.weight;
    for (size_t k = 0; k < sum.size(); ++k) sum[k] += w * src[k];
  }
}

// Filters one axis (0 = x, 1 = y, 2 = z) of `in` down to `n_out` texels.
Texture reduce_axis(const Texture& in, int axis, int n_out, MipEdge edge) {
  int dims[3] = {in.width, in.height, in.depth};
  const int n_in = dims[axis];
  dims[axis] = n_out;
  Texture out(dims[0], dims[1], dims[2], in.layers, in.channels);
  out.metadata = in.metadata;
  if (n_in == n_out) {
    out.data = in.data;
    return out;
  }
  const auto taps = axis_taps(n_in, n_out, edge);
  // One task per range of output rows (layer, z, y); each output texel sums
  // its taps in order from 0.0, independently of the others, so the result
  // does not depend on the split.
  const int rows = out.layers * out.depth * out.height;
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
    std::vector<double> sum(size_t(out.width) * size_t(in.channel_count()));
    for (int row = r.begin(); row < r.end(); ++row) {
      const int y = row % out.height, z = (row / out.height) % out.depth;
      const int layer = row / (out.height * out.depth);
      if (axis == 0)
        reduce_row_along_x(in, y, z, layer, taps, sum);
      else
        reduce_row_across(in, axis, y, z, layer, taps, sum);
      float* dst = out.texel(0, y, z, layer);
      for (size_t k = 0; k < sum.size(); ++k) dst[k] = float(sum[k]);
    }
  });
  return out;
}

// For sizes that halve exactly (n_in = 2 n_out: every level of a
// power-of-two texture) the taps are 2j and 2j + 1 with weight 0.5, and an
// axis of one texel that stays one is a copy. The three axis passes then
// run fused per output row: the input rows are reduced along x, their
// pairs along y, then along z, each step rounded to float as the pass's
// texture holds it and adding 0.0 + 0.5 a + 0.5 b in the passes' order, so
// the level is the same to the bit, without the two intermediate textures
// (a 16 MB and an 8 MB fresh buffer for a 128^3 RGBA level 1).
bool halves_exactly(int n_in, int n_out) { return n_in == 2 * n_out || (n_in == 1 && n_out == 1); }

inline float half_sum(float a, float b) {
  double acc = 0.0;
  acc += 0.5 * double(a);
  acc += 0.5 * double(b);
  return float(acc);
}

// row[0 .. n) of pairs along x (or a copy when x stays), nc channels.
void halve_row_along_x(const float* in, bool halve, int width, size_t nc, float* out) {
  const size_t n = size_t(width) * nc;
  if (!halve) {
    std::copy(in, in + n, out);
    return;
  }
  for (size_t x = 0; x < size_t(width); ++x)
    for (size_t c = 0; c < nc; ++c) out[x * nc + c] = half_sum(in[2 * x * nc + c], in[(2 * x + 1) * nc + c]);
}

void halve_rows(const float* a, const float* b, bool halve, size_t n, float* out) {
  if (!halve) {
    std::copy(a, a + n, out);
    return;
  }
  for (size_t k = 0; k < n; ++k) out[k] = half_sum(a[k], b[k]);
}

Texture halve_level(const Texture& in, int w, int h, int d) {
  Texture out(w, h, d, in.layers, in.channels);
  out.metadata = in.metadata;
  const bool hx = in.width == 2 * w, hy = in.height == 2 * h, hz = in.depth == 2 * d;
  const size_t nc = in.channels.size(), n = size_t(w) * nc;
  const int rows = out.layers * d * h;
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
    std::vector<float> along_x(4 * n), along_y(2 * n);  // [z pair][y pair] rows, [z pair] rows
    for (int row = r.begin(); row < r.end(); ++row) {
      const int y = row % h, z = (row / h) % d, layer = row / (h * d);
      for (int zz = 0; zz < (hz ? 2 : 1); ++zz) {
        for (int yy = 0; yy < (hy ? 2 : 1); ++yy)
          halve_row_along_x(in.texel(0, hy ? 2 * y + yy : y, hz ? 2 * z + zz : z, layer), hx, w,
                            nc, &along_x[size_t(2 * zz + yy) * n]);
        halve_rows(&along_x[size_t(2 * zz) * n], &along_x[size_t(2 * zz + 1) * n], hy, n,
                   &along_y[size_t(zz) * n]);
      }
      halve_rows(&along_y[0], &along_y[n], hz, n, out.texel(0, y, z, layer));
    }
  });
  return out;
}

}  // namespace

int mip_count(int width, int height, int depth) {
  int n = std::max({width, height, depth, 1});
  int levels = 1;
  while (n > 1) {
    n /= 2;
    ++levels;
  }
  return levels;
}

std::vector<Texture> build_lower_mips(const Texture& level0, MipEdge edge) {
  assert(level0.data.size() == level0.texel_count() * level0.channels.size());
  std::vector<Texture> chain;
  const int levels = mip_count(level0.width, level0.height, level0.depth);
  for (int level = 1; level < levels; ++level) {
    const Texture& prev = chain.empty() ? level0 : chain.back();
    const int w = std::max(1, prev.width / 2), h = std::max(1, prev.height / 2),
              d = std::max(1, prev.depth / 2);
    if (halves_exactly(prev.width, w) && halves_exactly(prev.height, h) &&
        halves_exactly(prev.depth, d)) {
      chain.push_back(halve_level(prev, w, h, d));
      continue;
    }
    Texture next = reduce_axis(prev, 0, std::max(1, prev.width / 2), edge);
    next = reduce_axis(next, 1, std::max(1, prev.height / 2), edge);
    next = reduce_axis(next, 2, std::max(1, prev.depth / 2), edge);
    chain.push_back(std::move(next));
  }
  return chain;
}

std::vector<Texture> build_mip_chain(const Texture& level0, MipEdge edge) {
  std::vector<Texture> chain{level0};
  for (Texture& level : build_lower_mips(level0, edge)) chain.push_back(std::move(level));
  return chain;
}

}  // namespace skybake

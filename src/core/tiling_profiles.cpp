#include "core/tiling_profiles.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

namespace {

// A line's stencils reach 4 faces before f and 5 texels after it (the turn's
// busier side: t_{f+3} = |d_{f+4} - d_{f+2}|, d_{f+4} = v(f + 5) - v(f + 4)).
constexpr int kPadBefore = 4;
constexpr int kPadAfter = 5;
// Lines read side by side along x: 8 doubles, one cache line of a plane.
constexpr int kLineBlock = 8;

// The loops below also get an AVX2 version, picked at load time where the
// CPU has it (twice the doubles per instruction). AVX2 without FMA: every
// operation is the same IEEE operation on the same operands in the same
// order, so both versions give the same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SKYBAKE_WIDE_VECTORS __attribute__((target_clones("avx2", "default")))
#else
#define SKYBAKE_WIDE_VECTORS
#endif

int wrap_index(int i, int len) {
  return ((i % len) + len) % len;
}

// The lines along `axis` of one plane (index `v` of the other axes; u
// counts the lines of the plane), every channel c:
// planes[c][i * lines + u] = texel i of line u. Each texel is read once,
// and the rows read are contiguous in memory for the y and z axes.
SKYBAKE_WIDE_VECTORS void read_planes(const Texture& t, int layer, int axis, int v, int lines,
                                      std::vector<std::vector<double>>& planes) {
  const size_t nc = t.channels.size();
  const int len = axis == 0 ? t.width : axis == 1 ? t.height : t.depth;
  if (axis == 0) {  // lines are rows: kLineBlock of them at a time fill whole cache lines
    for (int u0 = 0; u0 < lines; u0 += kLineBlock) {
      const int block = std::min(kLineBlock, lines - u0);
      const float* rows[kLineBlock];
      for (int b = 0; b < block; ++b) rows[b] = t.texel(0, u0 + b, v, layer);
      for (int i = 0; i < len; ++i)
        for (size_t c = 0; c < nc; ++c) {
          double* out = &planes[c][size_t(i) * lines + u0];
          for (int b = 0; b < block; ++b) out[b] = double(rows[b][size_t(i) * nc + c]);
        }
    }
    return;
  }
  for (int i = 0; i < len; ++i) {
    const float* row = axis == 1 ? t.texel(0, i, v, layer) : t.texel(0, v, i, layer);
    for (size_t c = 0; c < nc; ++c) {
      double* out = &planes[c][size_t(i) * lines];
      for (int u = 0; u < lines; ++u) out[u] = double(row[size_t(u) * nc + c]);
    }
  }
}

// Per line of the plane, sum over lags and texels of |v(i + lag) - v(i)|,
// texel by texel across the lines (each line's sum in the order of the
// definition), then added to `far` line after line.
SKYBAKE_WIDE_VECTORS void add_far_jumps(const std::vector<double>& plane, int len, int lines,
                                        const std::vector<int>& lags, std::vector<double>& line_far,
                                        long double& far) {
  std::fill(line_far.begin(), line_far.end(), 0.0);
  double* acc = line_far.data();
  for (int lag : lags)
    for (int i = 0; i < len; ++i) {
      const double* a = &plane[size_t(i) * lines];
      const double* b = &plane[size_t(i + lag < len ? i + lag : i + lag - len) * lines];
      for (int u = 0; u < lines; ++u) acc[u] += std::abs(b[u] - a[u]);
    }
  for (int u = 0; u < lines; ++u) far += line_far[u];
}

// The plane's lines one after another, each padded with the texels it
// wraps to: lines[u * stride + kPadBefore + i] = texel i (mod len) of line
// u, i in [-kPadBefore, len + kPadAfter).
SKYBAKE_WIDE_VECTORS void pad_lines(const std::vector<double>& plane, int len, int lines,
                                    std::vector<double>& out) {
  const size_t stride = size_t(len + kPadBefore + kPadAfter);
  for (int i = -kPadBefore; i < len + kPadAfter; ++i) {
    const double* row = &plane[size_t(wrap_index(i, len)) * lines];
    double* col = &out[size_t(i + kPadBefore)];
    for (int u = 0; u < lines; ++u) col[size_t(u) * stride] = row[u];
  }
}

// Scratch of one line: differences and turns, padded so every stencil
// reads in range (index 0 of each is face -kPadBefore).
struct LineScratch {
  std::vector<double> d, turn;
  explicit LineScratch(int len)
      : d(size_t(len + 2 * kPadBefore)), turn(size_t(len + 2 * kPadBefore)) {}
};

// Adds the faces of one padded line (x[-4 .. len + 5)) to the face sums.
SKYBAKE_WIDE_VECTORS void add_line(const double* __restrict x, int len, LineScratch& s,
                                   double* __restrict jump, double* __restrict jump_side,
                                   double* __restrict turn, double* __restrict turn_side) {
  double* __restrict d = s.d.data() + kPadBefore;  // d[-4 .. len + 4), signed
  for (int f = -kPadBefore; f < len + kPadBefore; ++f) d[f] = x[f + 1] - x[f];
  double* __restrict k = s.turn.data() + kPadBefore;  // k[-3 .. len + 3)
  for (int f = 1 - kPadBefore; f < len + kPadBefore - 1; ++f) k[f] = std::abs(d[f + 1] - d[f - 1]);
  for (int f = -kPadBefore; f < len + kPadBefore; ++f) d[f] = std::abs(d[f]);
  for (int f = 0; f < len; ++f) {
    jump[f] += d[f];
    jump_side[f] += std::max(d[f - 2] + d[f - 1], d[f + 1] + d[f + 2]) / 2;
    turn[f] += k[f];
    turn_side[f] += std::max(k[f - 3] + k[f - 2], k[f + 2] + k[f + 3]) / 2;
  }
}

}  // namespace

std::vector<TilingProfiles> compute_tiling_profiles(const Texture& t, int layer, int axis) {
  const int n[3] = {t.width, t.height, t.depth};
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  const int lines = n[u_axis], planes = n[v_axis];
  const size_t nc = t.channels.size();
  std::vector<int> lags;
  for (int k : {2, 3, 4, 5})
    if (len / k >= 2 && std::find(lags.begin(), lags.end(), len / k) == lags.end())
      lags.push_back(len / k);
  std::vector<TilingProfiles> profiles(nc);
  for (TilingProfiles& p : profiles)
    for (auto* v : {&p.jump, &p.jump_side, &p.turn, &p.turn_side}) v->assign(len, 0.0);
  std::vector<std::vector<double>> plane(nc, std::vector<double>(size_t(len) * size_t(lines)));
  const size_t stride = size_t(len + kPadBefore + kPadAfter);
  std::vector<double> padded(stride * size_t(lines));
  std::vector<double> line_far(static_cast<size_t>(lines));
  LineScratch scratch(len);
  std::vector<long double> far(nc, 0.0);
  for (int v = 0; v < planes; ++v) {
    read_planes(t, layer, axis, v, lines, plane);
    for (size_t c = 0; c < nc; ++c) {
      TilingProfiles& p = profiles[c];
      pad_lines(plane[c], len, lines, padded);
      for (int u = 0; u < lines; ++u)
        add_line(&padded[size_t(u) * stride + kPadBefore], len, scratch, p.jump.data(),
                 p.jump_side.data(), p.turn.data(), p.turn_side.data());
      add_far_jumps(plane[c], len, lines, lags, line_far, far[c]);
    }
  }
  const double total = double(size_t(lines) * size_t(planes));
  for (size_t c = 0; c < nc; ++c) {
    TilingProfiles& p = profiles[c];
    for (auto* v : {&p.jump, &p.jump_side, &p.turn, &p.turn_side})
      for (double& x : *v) x /= total;
    p.far = lags.empty() ? 0.0 : double(far[c] / (total * len * lags.size()));
  }
  return profiles;
}

}  // namespace skybake

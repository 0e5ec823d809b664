#include "core/tiling_profiles.hpp"

#include <algorithm>
#include <cmath>

#include "core/tiling_rgba.hpp"

namespace skybake {

namespace {

// A line's stencils reach 4 faces before f and 5 texels after it (the turn's
// busier side: t_{f+3} = |d_{f+4} - d_{f+2}|, d_{f+4} = v(f + 5) - v(f + 4)).
constexpr int kPadBefore = 4;
constexpr int kPadAfter = 5;
// Lines read side by side along x: 8 doubles, one cache line of a plane.
constexpr int kLineBlock = 8;
// Lines of the y and z axes taken together: a plane of 128 texels of 128
// lines in doubles is 128 KB, which stays in the cache across the passes.
constexpr size_t kChunk = 128;

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

// The lines along x of one plane (z = v; u counts the lines, y), every
// channel c: planes[c][i * lines + u] = texel i of line u, for the far
// jumps, which run across the lines. Each texel is read once; kLineBlock
// rows at a time fill whole cache lines of the planes.
SKYBAKE_WIDE_VECTORS void read_planes_x(const Texture& t, int layer, int v, int lines,
                                        std::vector<std::vector<double>>& planes) {
  const size_t nc = t.channels.size();
  const int len = t.width;
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
}

// Per line k of the plane, line_far[k] = the sum over lags and texels of
// |v(i + lag) - v(i)| in the order of the definition. kFarBlock lines at
// a time, their sums held in registers while the texels run (the rows of
// such a block, a cache line or two each, stay in L1), then the rest.
constexpr size_t kFarBlock = 16;
SKYBAKE_WIDE_VECTORS void add_far_jumps_by_line(const std::vector<double>& plane, int len,
                                                size_t count, const std::vector<int>& lags,
                                                std::vector<double>& line_far) {
  double* acc = line_far.data();
  size_t k0 = 0;
  for (; k0 + kFarBlock <= count; k0 += kFarBlock) {
    double sum[kFarBlock] = {};
    for (int lag : lags)
      for (int i = 0; i < len; ++i) {
        const double* a = &plane[size_t(i) * count + k0];
        const double* b = &plane[size_t(i + lag < len ? i + lag : i + lag - len) * count + k0];
        for (size_t k = 0; k < kFarBlock; ++k) sum[k] += std::abs(b[k] - a[k]);
      }
    std::copy(sum, sum + kFarBlock, acc + k0);
  }
  std::fill(acc + k0, acc + count, 0.0);
  for (int lag : lags)
    for (int i = 0; i < len; ++i) {
      const double* a = &plane[size_t(i) * count];
      const double* b = &plane[size_t(i + lag < len ? i + lag : i + lag - len) * count];
      for (size_t k = k0; k < count; ++k) acc[k] += std::abs(b[k] - a[k]);
    }
}

// The same for one channel's plane of `lines` lines, added to `far` line
// after line.
void add_far_jumps(const std::vector<double>& plane, int len, int lines,
                   const std::vector<int>& lags, std::vector<double>& line_far, long double& far) {
  add_far_jumps_by_line(plane, len, size_t(lines), lags, line_far);
  for (int u = 0; u < lines; ++u) far += line_far[size_t(u)];
}

// For the y and z axes the lines of a plane are its rows side by side:
// texel i of every line is row i of the plane, lines k = u * channels + c
// (u is x). They are taken kChunk at a time (a plane of doubles that stays
// in the cache): plane[i * count + k] = texel i of line k0 + k, one
// contiguous conversion per row, no channel split.
SKYBAKE_WIDE_VECTORS void read_rows(const float* const* rows, size_t k0, int len, size_t count,
                                    std::vector<double>& plane) {
  for (int i = 0; i < len; ++i) {
    const float* row = rows[i] + k0;
    double* out = &plane[size_t(i) * count];
    for (size_t k = 0; k < count; ++k) out[k] = double(row[k]);
  }
}

// The plane's lines one after another, each padded with the texels it
// wraps to: out[k * stride + kPadBefore + i] = texel i (mod len) of line
// k, i in [-kPadBefore, len + kPadAfter). kLineBlock texels of a line at a
// time: each line's cache line is written whole, not a double per visit.
SKYBAKE_WIDE_VECTORS void pad_lines(const std::vector<double>& plane, int len, size_t count,
                                    double* out) {
  const size_t stride = size_t(len + kPadBefore + kPadAfter);
  for (int i0 = -kPadBefore; i0 < len + kPadAfter; i0 += kLineBlock) {
    const int block = std::min(kLineBlock, len + kPadAfter - i0);
    const double* rows[kLineBlock];
    for (int b = 0; b < block; ++b) rows[b] = &plane[size_t(wrap_index(i0 + b, len)) * count];
    double* col = out + (i0 + kPadBefore);
    for (size_t k = 0; k < count; ++k)
      for (int b = 0; b < block; ++b) col[k * stride + size_t(b)] = rows[b][k];
  }
}

// The same for the x axis, whose lines are the rows (y = u) of plane z = v:
// each line is a row's channel, read along the row.
SKYBAKE_WIDE_VECTORS void pad_lines_along_x(const Texture& t, int layer, int v, int lines,
                                            double* out) {
  const int nc = t.channel_count(), len = t.width;
  const size_t stride = size_t(len + kPadBefore + kPadAfter);
  for (int u = 0; u < lines; ++u) {
    const float* row = t.texel(0, u, v, layer);
    for (int c = 0; c < nc; ++c) {
      double* line = out + (size_t(u) * nc + c) * stride + kPadBefore;
      for (int i = 0; i < len; ++i) line[i] = double(row[size_t(i) * nc + c]);
      for (int i = -kPadBefore; i < 0; ++i) line[i] = double(row[size_t(wrap_index(i, len)) * nc + c]);
      for (int i = len; i < len + kPadAfter; ++i)
        line[i] = double(row[size_t(wrap_index(i, len)) * nc + c]);
    }
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
  if (t.channels.size() == 4) return compute_tiling_profiles_rgba(t, layer, axis);
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
  // The lines of one plane, every channel: line k = u * nc + c, kChunk at
  // a time. Each channel's sums take its lines in plane order, as the
  // definition.
  const size_t count = size_t(lines) * nc;
  const size_t chunk = axis == 0 ? size_t(lines) : std::min(count, kChunk);
  const size_t stride = size_t(len + kPadBefore + kPadAfter);
  std::vector<double> padded(stride * (axis == 0 ? count : chunk));
  std::vector<double> line_far(chunk);
  LineScratch scratch(len);
  std::vector<long double> far(nc, 0.0);
  // x axis: one plane per channel (the far jumps run across its lines);
  // y and z: one plane of a chunk of every channel's lines.
  std::vector<std::vector<double>> plane(axis == 0 ? nc : 1,
                                         std::vector<double>(size_t(len) * chunk));
  std::vector<const float*> rows(size_t(len), nullptr);
  auto add_lines = [&](size_t k0, size_t n) {
    for (size_t k = 0; k < n; ++k) {
      TilingProfiles& p = profiles[(k0 + k) % nc];
      add_line(&padded[k * stride + kPadBefore], len, scratch, p.jump.data(), p.jump_side.data(),
               p.turn.data(), p.turn_side.data());
    }
  };
  for (int v = 0; v < planes; ++v) {
    if (axis == 0) {
      read_planes_x(t, layer, v, lines, plane);
      for (size_t c = 0; c < nc; ++c) add_far_jumps(plane[c], len, lines, lags, line_far, far[c]);
      pad_lines_along_x(t, layer, v, lines, padded.data());
      add_lines(0, count);
      continue;
    }
    for (int i = 0; i < len; ++i)
      rows[size_t(i)] = axis == 1 ? t.texel(0, i, v, layer) : t.texel(0, v, i, layer);
    for (size_t k0 = 0; k0 < count; k0 += chunk) {
      const size_t n = std::min(chunk, count - k0);
      read_rows(rows.data(), k0, len, n, plane[0]);
      add_far_jumps_by_line(plane[0], len, n, lags, line_far);
      for (size_t k = 0; k < n; ++k) far[(k0 + k) % nc] += line_far[k];
      pad_lines(plane[0], len, n, padded.data());
      add_lines(k0, n);
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

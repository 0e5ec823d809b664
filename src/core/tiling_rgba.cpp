#include "core/tiling_rgba.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "core/simd_switches.hpp"

namespace skybake {

// Named: the unity build puts this file beside core/tiling_profiles.cpp.
namespace tiling_rgba {

// Four doubles, a texel's channels. GCC's vector extension lowers each
// operation to one AVX2 or two SSE2 instructions, the same IEEE operation
// per lane either way (no FMA: the AVX2 target has none), so both builds
// give the same bits (core/simd_switches.hpp). Values of this type never
// cross a function boundary: the bodies below are inlined into the AVX2
// and the SSE2 function that call them.
typedef double v4d __attribute__((vector_size(32)));
typedef float v4f_any __attribute__((vector_size(16), aligned(4)));  // any float address
typedef long long v4l __attribute__((vector_size(32)));
const v4l kAbsMask = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL, 0x7fffffffffffffffLL,
                      0x7fffffffffffffffLL};
#define SKYBAKE_BODY inline __attribute__((always_inline))

struct alignas(32) Lanes {
  double c[4];
};

// As core/tiling_profiles.cpp: a line's stencils reach 4 faces before f and
// 5 texels after it.
constexpr int kPadBefore = 4;
constexpr int kPadAfter = 5;
// Lines whose far jumps run side by side: four independent chains of sums
// instead of one (each chain adds in the definition's order).
constexpr int kBlock = 4;
// Lines whose faces are added together (their terms stay in L1).
constexpr int kFaceLines = 2;
// Lines read from the texture together: along y and z each read is then
// 32 texels of a row (8 cache lines) rather than one cache line per row.
constexpr int kChunk = 32;

int wrap_index(int i, int len) { return ((i % len) + len) % len; }

// Where the lines of one plane are (see compute_tiling_profiles).
struct PlaneLines {
  const float* const* rows;  // y and z: texel i of line u at rows[i] + 4 u
  const Texture* t;          // x: line u is the row (y = u, z = v)
  int axis, v, layer, len;
};

// Scratch: kChunk padded lines, texel i of line g at
// x[g * stride + kPadBefore + i], i in [-kPadBefore, len + kPadAfter); and
// the terms of kBlock lines (line_terms).
struct Scratch {
  size_t stride;
  std::vector<Lanes> x, ad, k, p, q;
  explicit Scratch(int len)
      : stride(size_t(len + kPadBefore + kPadAfter)), x(stride * kChunk), ad(stride * kFaceLines),
        k(stride * kFaceLines), p(stride * kFaceLines), q(stride * kFaceLines) {}
};

// The face sums, channel in the lanes: jump[f].c[ch].
struct FaceSums {
  std::vector<Lanes> jump, jump_side, turn, turn_side;
  std::vector<long double> far = std::vector<long double>(4, 0.0L);
  explicit FaceSums(int len) : jump(size_t(len)), jump_side(size_t(len)), turn(size_t(len)),
                               turn_side(size_t(len)) {}
};

// Helpers as macros: a function passing v4d by value would change its
// calling convention between the two builds.
// Texel p's four floats as doubles.
#define SKYBAKE_LOAD_TEXEL(p) __builtin_convertvector(*reinterpret_cast<const v4f_any*>(p), v4d)
// std::abs per lane: the sign bit cleared.
#define SKYBAKE_ABS_LANES(v) ((v4d)((v4l)(v) & kAbsMask))
// std::max(a, b) per lane: a unless a < b (NaN and signed zeros alike).
#define SKYBAKE_MAX_LANES(a, b) ((a) < (b) ? (b) : (a))

// Lines u0 .. u0 + n - 1 (n <= kChunk) of the plane into the scratch,
// padded by wrapping.
SKYBAKE_BODY void fill_lines(const PlaneLines& pl, int u0, int n, Scratch& s) {
  v4d* x = reinterpret_cast<v4d*>(s.x.data()) + kPadBefore;
  const int len = pl.len;
  if (pl.axis == 0) {
    for (int g = 0; g < n; ++g) {
      const float* row = pl.t->texel(0, u0 + g, pl.v, pl.layer);
      v4d* line = x + size_t(g) * s.stride;
      for (int i = 0; i < len; ++i) line[i] = SKYBAKE_LOAD_TEXEL(row + 4 * size_t(i));
      for (int i = -kPadBefore; i < 0; ++i) line[i] = line[wrap_index(i, len)];
      for (int i = len; i < len + kPadAfter; ++i) line[i] = line[wrap_index(i, len)];
    }
    return;
  }
  for (int i = -kPadBefore; i < len + kPadAfter; ++i) {
    const float* row = pl.rows[wrap_index(i, len)] + 4 * size_t(u0);
    // Signed: i runs from -kPadBefore, and an unsigned offset would wrap.
    for (int g = 0; g < n; ++g)
      x[std::ptrdiff_t(g) * std::ptrdiff_t(s.stride) + i] = SKYBAKE_LOAD_TEXEL(row + 4 * g);
  }
}

// Per line g < n of the block: the sum over lags and texels of
// |v(i + lag) - v(i)|, lags in order, i in order, from 0.
SKYBAKE_BODY void far_block(const Scratch& s, int g0, int len, int n, const std::vector<int>& lags,
                            Lanes* out) {
  const v4d* x = reinterpret_cast<const v4d*>(s.x.data()) + kPadBefore + size_t(g0) * s.stride;
  const size_t st = s.stride;
  v4d sum[kBlock] = {};
  for (int lag : lags) {
    for (int i = 0; i < len - lag; ++i)
      for (int g = 0; g < kBlock; ++g)
        sum[g] += SKYBAKE_ABS_LANES(x[g * st + size_t(i + lag)] - x[g * st + size_t(i)]);
    for (int i = len - lag; i < len; ++i)
      for (int g = 0; g < kBlock; ++g)
        sum[g] += SKYBAKE_ABS_LANES(x[g * st + size_t(i + lag - len)] - x[g * st + size_t(i)]);
  }
  for (int g = 0; g < n; ++g) std::memcpy(&out[g], &sum[g], sizeof(Lanes));
}

// One padded line's terms (the definition's add_line): |d_i|, the turn
// k_i = |d_{i+1} - d_{i-1}|, and the busier sides' pair sums
// p_i = |d_i| + |d_{i+1}| and q_i = k_i + k_{i+1}, each computed once for
// the two faces that use it (the same operands in the same order). One pass,
// the differences carried in registers; line g's terms at g * stride.
SKYBAKE_BODY void line_terms(const v4d* x, int len, Scratch& s, int g) {
  const size_t at = size_t(g) * s.stride + kPadBefore;
  v4d* ad = reinterpret_cast<v4d*>(s.ad.data()) + at;
  v4d* k = reinterpret_cast<v4d*>(s.k.data()) + at;
  v4d* p = reinterpret_cast<v4d*>(s.p.data()) + at;
  v4d* q = reinterpret_cast<v4d*>(s.q.data()) + at;
  v4d d_before = x[-3] - x[-4];  // d_{j-1}
  v4d d_here = x[-2] - x[-3];    // d_j
  v4d ad_here = SKYBAKE_ABS_LANES(d_here);
  v4d k_before = {0.0, 0.0, 0.0, 0.0};  // k_{j-1}; q_{-4} is never read
  ad[-3] = ad_here;
  // Faces f in [0, len) read p over [-2, len], q over [-3, len + 1].
  for (int j = -3; j <= len + 2; ++j) {
    const v4d d_next = x[j + 2] - x[j + 1];
    const v4d k_here = SKYBAKE_ABS_LANES(d_next - d_before);
    const v4d ad_next = SKYBAKE_ABS_LANES(d_next);
    ad[j + 1] = ad_next;
    k[j] = k_here;
    p[j] = ad_here + ad_next;
    q[j - 1] = k_before + k_here;
    d_before = d_here;
    d_here = d_next;
    ad_here = ad_next;
    k_before = k_here;
  }
}

// The faces of lines 0 .. m - 1 of the terms, added line after line to
// each face's sums (held in registers across the lines).
SKYBAKE_BODY void add_faces(const Scratch& s, int len, int m, FaceSums& sums) {
  const v4d* ad = reinterpret_cast<const v4d*>(s.ad.data()) + kPadBefore;
  const v4d* k = reinterpret_cast<const v4d*>(s.k.data()) + kPadBefore;
  const v4d* p = reinterpret_cast<const v4d*>(s.p.data()) + kPadBefore;
  const v4d* q = reinterpret_cast<const v4d*>(s.q.data()) + kPadBefore;
  v4d* jump = reinterpret_cast<v4d*>(sums.jump.data());
  v4d* jump_side = reinterpret_cast<v4d*>(sums.jump_side.data());
  v4d* turn = reinterpret_cast<v4d*>(sums.turn.data());
  v4d* turn_side = reinterpret_cast<v4d*>(sums.turn_side.data());
  const size_t st = s.stride;
  for (int f = 0; f < len; ++f) {
    v4d j = jump[f], js = jump_side[f], t = turn[f], ts = turn_side[f];
    for (int g = 0; g < m; ++g) {
      const std::ptrdiff_t o = std::ptrdiff_t(g) * std::ptrdiff_t(st) + f;  // o - 3 may be < 0
      j += ad[o];
      js += SKYBAKE_MAX_LANES(p[o - 2], p[o + 1]) / 2;
      t += k[o];
      ts += SKYBAKE_MAX_LANES(q[o - 3], q[o + 2]) / 2;
    }
    jump[f] = j;
    jump_side[f] = js;
    turn[f] = t;
    turn_side[f] = ts;
  }
}

// Along y and z, the texels of the next kChunk lines (from line u1 on; past
// a row's end along z: the next plane's row), a share of the rows for each
// line g of n summed meanwhile: rows a plane apart defeat the hardware's
// prefetch, and a burst of prefetches would wait for line-fill buffers.
SKYBAKE_BODY void prefetch_next(const PlaneLines& pl, int u1, int g, int n) {
  if (pl.axis == 0) return;
  for (int i = g * pl.len / n; i < (g + 1) * pl.len / n; ++i)
    for (int b = 0; b < 4 * kChunk; b += 16) __builtin_prefetch(pl.rows[i] + 4 * size_t(u1) + b);
}

// Lines u0 .. u0 + n - 1 of a plane: read once, then kBlock lines at a
// time their far jumps and the faces of each line, lines in order.
SKYBAKE_BODY void add_lines(const PlaneLines& pl, int u0, int n, const std::vector<int>& lags,
                            Scratch& s, FaceSums& sums) {
  fill_lines(pl, u0, n, s);
  const v4d* x = reinterpret_cast<const v4d*>(s.x.data()) + kPadBefore;
  for (int g0 = 0; g0 < n; g0 += kBlock) {
    const int m = std::min(kBlock, n - g0);
    Lanes far[kBlock];
    far_block(s, g0, pl.len, m, lags, far);
    for (int g = 0; g < m; ++g)
      for (int c = 0; c < 4; ++c) sums.far[size_t(c)] += far[g].c[c];
    for (int g = 0; g < m; ++g) {
      prefetch_next(pl, u0 + kChunk, g0 + g, n);
      line_terms(x + size_t(g0 + g) * s.stride, pl.len, s, g % kFaceLines);
      if (g % kFaceLines == kFaceLines - 1) add_faces(s, pl.len, kFaceLines, sums);
    }
    if (m % kFaceLines) add_faces(s, pl.len, m % kFaceLines, sums);
  }
}

#if SKYBAKE_HAS_AVX2
SKYBAKE_AVX2 void add_plane_avx2(const PlaneLines& pl, int lines, const std::vector<int>& lags,
                                 Scratch& s, FaceSums& sums) {
  for (int u0 = 0; u0 < lines; u0 += kChunk)
    add_lines(pl, u0, std::min(kChunk, lines - u0), lags, s, sums);
}
#endif

void add_plane(const PlaneLines& pl, int lines, const std::vector<int>& lags, Scratch& s,
               FaceSums& sums) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) return add_plane_avx2(pl, lines, lags, s, sums);
#endif
  for (int u0 = 0; u0 < lines; u0 += kChunk)
    add_lines(pl, u0, std::min(kChunk, lines - u0), lags, s, sums);
}

}  // namespace tiling_rgba

std::vector<TilingProfiles> compute_tiling_profiles_rgba(const Texture& t, int layer, int axis) {
  const int n[3] = {t.width, t.height, t.depth};
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  const int lines = n[u_axis], planes = n[v_axis];
  std::vector<int> lags;
  for (int k : {2, 3, 4, 5})
    if (len / k >= 2 && std::find(lags.begin(), lags.end(), len / k) == lags.end())
      lags.push_back(len / k);
  tiling_rgba::Scratch scratch(len);
  tiling_rgba::FaceSums sums(len);
  std::vector<const float*> rows(size_t(len), nullptr);
  tiling_rgba::PlaneLines pl{rows.data(), &t, axis, 0, layer, len};
  for (int v = 0; v < planes; ++v) {
    pl.v = v;
    if (axis != 0)
      for (int i = 0; i < len; ++i)
        rows[size_t(i)] = axis == 1 ? t.texel(0, i, v, layer) : t.texel(0, v, i, layer);
    tiling_rgba::add_plane(pl, lines, lags, scratch, sums);
  }
  const double total = double(size_t(lines) * size_t(planes));
  std::vector<TilingProfiles> profiles(4);
  for (int c = 0; c < 4; ++c) {
    TilingProfiles& p = profiles[size_t(c)];
    const std::pair<std::vector<double>*, const std::vector<tiling_rgba::Lanes>*> parts[] = {
        {&p.jump, &sums.jump}, {&p.jump_side, &sums.jump_side},
        {&p.turn, &sums.turn}, {&p.turn_side, &sums.turn_side}};
    for (const auto& [out, in] : parts) {
      out->resize(size_t(len));
      for (int f = 0; f < len; ++f) (*out)[size_t(f)] = (*in)[size_t(f)].c[c] / total;
    }
    p.far = lags.empty() ? 0.0 : double(sums.far[size_t(c)] / (total * len * lags.size()));
  }
  return profiles;
}

}  // namespace skybake

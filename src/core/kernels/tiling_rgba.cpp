// tiling_rgba_sums over lanes (Highway, every target from one source): a
// texel's four channels are one Quad (as many vectors as the target needs
// for four doubles), every lane doing the definition's IEEE operations on
// the same operands in the same order; std::abs clears the sign bit and
// std::max(a, b) is Max(b, a) for every non-NaN value, signed zeros
// included (docs/architecture.md "Kernels"). So every target gives the same
// bits (tests/core/tiling_profiles_test.cpp). See the header.
#include "core/kernels/tiling_rgba.hpp"

#include <algorithm>
#include <cstddef>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/kernels/tiling_rgba.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// As core/tiling_profiles.cpp: a line's stencils reach 4 faces before f and
// 5 texels after it.
constexpr int kRgbaPadBefore = 4;
constexpr int kRgbaPadAfter = 5;
// Lines whose far jumps run side by side: four independent chains of sums
// instead of one (each chain adds in the definition's order).
constexpr int kRgbaBlock = 4;
// Lines whose faces are added together (their terms stay in L1).
constexpr int kRgbaFaceLines = 2;
// Lines read from the texture together: along y and z each read is then
// 32 texels of a row (8 cache lines) rather than one cache line per row.
constexpr int kRgbaChunk = 32;

// A texel's four channels in lanes: one vector of four doubles, two of two
// or four of one.
using DQ = hn::CappedTag<double, 4>;
constexpr size_t kQuadLanes = hn::MaxLanes(DQ());
constexpr size_t kQuadParts = 4 / kQuadLanes;
struct Quad {
  hn::Vec<DQ> v[kQuadParts];
};

HWY_INLINE Quad LoadQuad(const TexelChannels& t) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Load(DQ(), t.c + k * kQuadLanes);
  return q;
}
HWY_INLINE void StoreQuad(const Quad& q, TexelChannels& t) {
  for (size_t k = 0; k < kQuadParts; ++k) hn::Store(q.v[k], DQ(), t.c + k * kQuadLanes);
}
// A texel's four floats widened to double.
HWY_INLINE Quad LoadTexel(const float* p) {
  const hn::Rebind<float, DQ> df;
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k)
    q.v[k] = hn::PromoteTo(DQ(), hn::LoadU(df, p + k * kQuadLanes));
  return q;
}
HWY_INLINE Quad ZeroQuad() {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Zero(DQ());
  return q;
}
// a + b, a - b, |a|, std::max(a, b) and a / 2 (the same bits as a * 0.5,
// both the one rounding of the same value), lane by lane.
HWY_INLINE Quad Plus(const Quad& a, const Quad& b) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Add(a.v[k], b.v[k]);
  return q;
}
HWY_INLINE Quad Minus(const Quad& a, const Quad& b) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Sub(a.v[k], b.v[k]);
  return q;
}
HWY_INLINE Quad Magnitude(const Quad& a) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Abs(a.v[k]);
  return q;
}
HWY_INLINE Quad Larger(const Quad& a, const Quad& b) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k)
    q.v[k] = hn::Max(b.v[k], a.v[k]);
  return q;
}
HWY_INLINE Quad Halved(const Quad& a) {
  Quad q;
  for (size_t k = 0; k < kQuadParts; ++k) q.v[k] = hn::Mul(a.v[k], hn::Set(DQ(), 0.5));
  return q;
}

int WrapIndex(int i, int len) { return ((i % len) + len) % len; }

// Where the lines of one plane are (see TilingRgbaSumsOf).
struct PlaneLines {
  const float* const* rows;  // y and z: texel i of line u at rows[i] + 4 u
  const Texture* t;          // x: line u is the row (y = u, z = v)
  int axis, v, layer, len;
};

// Scratch: kRgbaChunk padded lines, texel i of line g at
// x[g * stride + kRgbaPadBefore + i], i in [-kRgbaPadBefore, len +
// kRgbaPadAfter); and the terms of kRgbaFaceLines lines (LineTerms).
struct RgbaScratch {
  size_t stride;
  std::vector<TexelChannels> x, ad, k, p, q;
  explicit RgbaScratch(int len)
      : stride(size_t(len + kRgbaPadBefore + kRgbaPadAfter)), x(stride * kRgbaChunk),
        ad(stride * kRgbaFaceLines), k(stride * kRgbaFaceLines), p(stride * kRgbaFaceLines),
        q(stride * kRgbaFaceLines) {}
};

// Lines u0 .. u0 + n - 1 (n <= kRgbaChunk) of the plane into the scratch,
// padded by wrapping.
HWY_INLINE void FillLines(const PlaneLines& pl, int u0, int n, RgbaScratch& s) {
  TexelChannels* x = s.x.data() + kRgbaPadBefore;
  const int len = pl.len;
  if (pl.axis == 0) {
    for (int g = 0; g < n; ++g) {
      const float* row = pl.t->texel(0, u0 + g, pl.v, pl.layer);
      TexelChannels* line = x + size_t(g) * s.stride;
      for (int i = 0; i < len; ++i) StoreQuad(LoadTexel(row + 4 * size_t(i)), line[i]);
      for (int i = -kRgbaPadBefore; i < 0; ++i) line[i] = line[WrapIndex(i, len)];
      for (int i = len; i < len + kRgbaPadAfter; ++i) line[i] = line[WrapIndex(i, len)];
    }
    return;
  }
  for (int i = -kRgbaPadBefore; i < len + kRgbaPadAfter; ++i) {
    const float* row = pl.rows[WrapIndex(i, len)] + 4 * size_t(u0);
    // Signed: i runs from -kRgbaPadBefore, and an unsigned offset would wrap.
    for (int g = 0; g < n; ++g)
      StoreQuad(LoadTexel(row + 4 * g), x[std::ptrdiff_t(g) * std::ptrdiff_t(s.stride) + i]);
  }
}

// Per line g < n of the block: the sum over lags and texels of
// |v(i + lag) - v(i)|, lags in order, i in order, from 0.
HWY_INLINE void FarBlock(const RgbaScratch& s, int g0, int len, int n,
                         const std::vector<int>& lags, TexelChannels* out) {
  const TexelChannels* x = s.x.data() + kRgbaPadBefore + size_t(g0) * s.stride;
  const size_t st = s.stride;
  Quad sum[kRgbaBlock];
  for (int g = 0; g < kRgbaBlock; ++g) sum[g] = ZeroQuad();
  for (int lag : lags) {
    for (int i = 0; i < len - lag; ++i)
      for (int g = 0; g < kRgbaBlock; ++g)
        sum[g] = Plus(sum[g], Magnitude(Minus(LoadQuad(x[g * st + size_t(i + lag)]),
                                              LoadQuad(x[g * st + size_t(i)]))));
    for (int i = len - lag; i < len; ++i)
      for (int g = 0; g < kRgbaBlock; ++g)
        sum[g] = Plus(sum[g], Magnitude(Minus(LoadQuad(x[g * st + size_t(i + lag - len)]),
                                              LoadQuad(x[g * st + size_t(i)]))));
  }
  for (int g = 0; g < n; ++g) StoreQuad(sum[g], out[g]);
}

// One padded line's terms (the definition's add_line): |d_i|, the turn
// k_i = |d_{i+1} - d_{i-1}|, and the busier sides' pair sums
// p_i = |d_i| + |d_{i+1}| and q_i = k_i + k_{i+1}, each computed once for
// the two faces that use it (the same operands in the same order). One pass,
// the differences carried in registers; line g's terms at g * stride.
HWY_INLINE void LineTerms(const TexelChannels* x, int len, RgbaScratch& s, int g) {
  const size_t at = size_t(g) * s.stride + kRgbaPadBefore;
  TexelChannels* ad = s.ad.data() + at;
  TexelChannels* k = s.k.data() + at;
  TexelChannels* p = s.p.data() + at;
  TexelChannels* q = s.q.data() + at;
  Quad d_before = Minus(LoadQuad(x[-3]), LoadQuad(x[-4]));  // d_{j-1}
  Quad d_here = Minus(LoadQuad(x[-2]), LoadQuad(x[-3]));    // d_j
  Quad ad_here = Magnitude(d_here);
  Quad k_before = ZeroQuad();  // k_{j-1}; q_{-4} is never read
  StoreQuad(ad_here, ad[-3]);
  // Faces f in [0, len) read p over [-2, len], q over [-3, len + 1].
  for (int j = -3; j <= len + 2; ++j) {
    const Quad d_next = Minus(LoadQuad(x[j + 2]), LoadQuad(x[j + 1]));
    const Quad k_here = Magnitude(Minus(d_next, d_before));
    const Quad ad_next = Magnitude(d_next);
    StoreQuad(ad_next, ad[j + 1]);
    StoreQuad(k_here, k[j]);
    StoreQuad(Plus(ad_here, ad_next), p[j]);
    StoreQuad(Plus(k_before, k_here), q[j - 1]);
    d_before = d_here;
    d_here = d_next;
    ad_here = ad_next;
    k_before = k_here;
  }
}

// The faces of lines 0 .. m - 1 of the terms, added line after line to
// each face's sums (held in registers across the lines).
HWY_INLINE void AddFaces(const RgbaScratch& s, int len, int m, TilingRgbaSums& sums) {
  const TexelChannels* ad = s.ad.data() + kRgbaPadBefore;
  const TexelChannels* k = s.k.data() + kRgbaPadBefore;
  const TexelChannels* p = s.p.data() + kRgbaPadBefore;
  const TexelChannels* q = s.q.data() + kRgbaPadBefore;
  const size_t st = s.stride;
  for (int f = 0; f < len; ++f) {
    Quad j = LoadQuad(sums.jump[size_t(f)]), js = LoadQuad(sums.jump_side[size_t(f)]);
    Quad t = LoadQuad(sums.turn[size_t(f)]), ts = LoadQuad(sums.turn_side[size_t(f)]);
    for (int g = 0; g < m; ++g) {
      const std::ptrdiff_t o = std::ptrdiff_t(g) * std::ptrdiff_t(st) + f;  // o - 3 may be < 0
      j = Plus(j, LoadQuad(ad[o]));
      js = Plus(js, Halved(Larger(LoadQuad(p[o - 2]), LoadQuad(p[o + 1]))));
      t = Plus(t, LoadQuad(k[o]));
      ts = Plus(ts, Halved(Larger(LoadQuad(q[o - 3]), LoadQuad(q[o + 2]))));
    }
    StoreQuad(j, sums.jump[size_t(f)]);
    StoreQuad(js, sums.jump_side[size_t(f)]);
    StoreQuad(t, sums.turn[size_t(f)]);
    StoreQuad(ts, sums.turn_side[size_t(f)]);
  }
}

// Along y and z, the texels of the next kRgbaChunk lines (from line u1 on;
// past a row's end along z: the next plane's row), a share of the rows for
// each line g of n summed meanwhile: rows a plane apart defeat the
// hardware's prefetch, and a burst of prefetches would wait for line-fill
// buffers.
HWY_INLINE void PrefetchNext(const PlaneLines& pl, int u1, int g, int n) {
  if (pl.axis == 0) return;
  for (int i = g * pl.len / n; i < (g + 1) * pl.len / n; ++i)
    for (int b = 0; b < 4 * kRgbaChunk; b += 16) __builtin_prefetch(pl.rows[i] + 4 * size_t(u1) + b);
}

// Lines u0 .. u0 + n - 1 of a plane: read once, then kRgbaBlock lines at a
// time their far jumps and the faces of each line, lines in order.
HWY_INLINE void AddLines(const PlaneLines& pl, int u0, int n, const std::vector<int>& lags,
                         RgbaScratch& s, TilingRgbaSums& sums) {
  FillLines(pl, u0, n, s);
  const TexelChannels* x = s.x.data() + kRgbaPadBefore;
  for (int g0 = 0; g0 < n; g0 += kRgbaBlock) {
    const int m = std::min(kRgbaBlock, n - g0);
    TexelChannels far[kRgbaBlock];
    FarBlock(s, g0, pl.len, m, lags, far);
    for (int g = 0; g < m; ++g)
      for (int c = 0; c < 4; ++c) sums.far[c] += far[g].c[c];
    for (int g = 0; g < m; ++g) {
      PrefetchNext(pl, u0 + kRgbaChunk, g0 + g, n);
      LineTerms(x + size_t(g0 + g) * s.stride, pl.len, s, g % kRgbaFaceLines);
      if (g % kRgbaFaceLines == kRgbaFaceLines - 1) AddFaces(s, pl.len, kRgbaFaceLines, sums);
    }
    if (m % kRgbaFaceLines) AddFaces(s, pl.len, m % kRgbaFaceLines, sums);
  }
}

// Every plane across the axis, lines in plane order.
void TilingRgbaSumsOf(const Texture& t, int layer, int axis, const std::vector<int>& lags,
                      TilingRgbaSums& sums) {
  const int n[3] = {t.width, t.height, t.depth};
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  const int lines = n[u_axis], planes = n[v_axis];
  RgbaScratch scratch(len);
  std::vector<const float*> rows(size_t(len), nullptr);
  PlaneLines pl{rows.data(), &t, axis, 0, layer, len};
  for (int v = 0; v < planes; ++v) {
    pl.v = v;
    if (axis != 0)
      for (int i = 0; i < len; ++i)
        rows[size_t(i)] = axis == 1 ? t.texel(0, i, v, layer) : t.texel(0, v, i, layer);
    for (int u0 = 0; u0 < lines; u0 += kRgbaChunk)
      AddLines(pl, u0, std::min(kRgbaChunk, lines - u0), lags, scratch, sums);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(TilingRgbaSumsOf);

TilingRgbaSums tiling_rgba_sums(const Texture& t, int layer, int axis,
                                const std::vector<int>& lags) {
  const int n[3] = {t.width, t.height, t.depth};
  const size_t len = size_t(n[axis]);
  TilingRgbaSums sums;
  for (std::vector<TexelChannels>* v : {&sums.jump, &sums.jump_side, &sums.turn, &sums.turn_side})
    v->assign(len, TexelChannels{{0.0, 0.0, 0.0, 0.0}});
  HWY_DYNAMIC_DISPATCH(TilingRgbaSumsOf)(t, layer, axis, lags, sums);
  return sums;
}

}  // namespace skybake
#endif  // HWY_ONCE

// The loop of one node of a multiple-scattering row over lanes (Highway,
// every target from one source). See the header.
#include "atmosphere/kernels/node_slice_reads.hpp"

#include <algorithm>
#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/node_slice_reads.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/node_taps-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// SunCosineTapsFloat::tap of the texels from x, and their reads' texels.
template <class DF>
HWY_INLINE void NodeTaps(DF df, const SunCosineTapsFloat& k, const NodeRow& q, int x) {
  const hn::Rebind<int32_t, DF> di;
  hn::Vec<DF> w;
  const hn::Vec<DF> i =
      MuSTap(df, k, NodeCosinesFloat(df, q.r, q.s, q.inv_r_i, q.mu_s, q.nu, x), w);
  hn::StoreU(w, df, q.lw + x);
  const hn::Vec<decltype(di)> tap = WholeToInt(df, i);
  hn::StoreU(hn::Add(tap, hn::LoadU(di, q.nu_i0 + x)), di, q.at0 + x);
  hn::StoreU(hn::Add(tap, hn::LoadU(di, q.nu_i1 + x)), di, q.at1 + x);
}

// The read of texel x: sum += wS lerp(lerp(s00, s01, lw), lerp(s10, s11,
// lw), nw), or with one nu slice (NodeRow::single) sum += wS lerp(s00, s01,
// lw); R G B and the pad a lane each, Lanes(d4) channels at a time.
template <class D4>
HWY_INLINE void NodeRead(D4 d4, const Rgb4* slice, const NodeRow& q, const Rgb4& wS, int x,
                         bool one_slice, Rgb4& sum) {
  using V = hn::Vec<D4>;
  const Rgb4* s0 = slice + q.at0[x];
  const Rgb4* s1 = slice + q.at1[x];
  const float lw = q.lw[x], nw = q.nu_w[x];
  const V l1 = hn::Set(d4, lw), l0 = hn::Set(d4, 1.0f - lw);
  const V n1 = hn::Set(d4, nw), n0 = hn::Set(d4, 1.0f - nw);
  for (size_t c = 0; c < 4; c += hn::Lanes(d4)) {
    const V a = hn::Add(hn::Mul(l0, hn::LoadU(d4, s0[0].v + c)), hn::Mul(l1, hn::LoadU(d4, s0[1].v + c)));
    V L = a;
    if (!one_slice) {
      const V b =
          hn::Add(hn::Mul(l0, hn::LoadU(d4, s1[0].v + c)), hn::Mul(l1, hn::LoadU(d4, s1[1].v + c)));
      L = hn::Add(hn::Mul(n0, a), hn::Mul(n1, b));
    }
    hn::StoreU(hn::Add(hn::LoadU(d4, sum.v + c), hn::Mul(hn::LoadU(d4, wS.v + c), L)), d4,
               sum.v + c);
  }
}

#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3
// NodeRead of texels x and x + 1 in eight lanes: a 256-bit load takes a
// texel's s00 and s01 (or s10 and s11) together, regrouped into (s00 of x,
// s00 of x + 1) and (s01 of x, s01 of x + 1).
HWY_INLINE void NodeReadPair(const Rgb4* slice, const NodeRow& q, const Rgb4& wS, int x,
                             bool one_slice, Rgb4* sum) {
  const hn::Full256<float> d8;
  const hn::Full128<float> d4;
  using V = hn::Vec<decltype(d8)>;
  auto pair = [&](float a, float b) { return hn::Combine(d8, hn::Set(d4, b), hn::Set(d4, a)); };
  const V one = hn::Set(d8, 1.0f);
  const V a0 = hn::LoadU(d8, slice[q.at0[x]].v), a1 = hn::LoadU(d8, slice[q.at0[x + 1]].v);
  const V l1 = pair(q.lw[x], q.lw[x + 1]), l0 = hn::Sub(one, l1);
  V L = hn::Add(hn::Mul(l0, hn::ConcatLowerLower(d8, a1, a0)),
                hn::Mul(l1, hn::ConcatUpperUpper(d8, a1, a0)));
  if (!one_slice) {
    const V b0 = hn::LoadU(d8, slice[q.at1[x]].v), b1 = hn::LoadU(d8, slice[q.at1[x + 1]].v);
    const V b = hn::Add(hn::Mul(l0, hn::ConcatLowerLower(d8, b1, b0)),
                        hn::Mul(l1, hn::ConcatUpperUpper(d8, b1, b0)));
    const V n1 = pair(q.nu_w[x], q.nu_w[x + 1]), n0 = hn::Sub(one, n1);
    L = hn::Add(hn::Mul(n0, L), hn::Mul(n1, b));
  }
  const V ws = hn::Combine(d8, hn::LoadU(d4, wS.v), hn::LoadU(d4, wS.v));
  hn::StoreU(hn::Add(hn::LoadU(d8, sum[x].v), hn::Mul(ws, L)), d8, sum[x].v);
}
#endif

}  // namespace

// The loops read local copies of the constants: through the references,
// the compiler reloaded them after every store (a store of floats might
// have changed them).
void AddNodeSliceReads(const NodeRow& row_in, const SunCosineTapsFloat& taps_in,
                       const Rgb4* slice, const Rgb4& wS_in, int end, Rgb4* sum) {
  const NodeRow row = row_in;
  const SunCosineTapsFloat taps = taps_in;
  const Rgb4 wS = wS_in;
  const hn::ScalableTag<float> df;
  const hn::CappedTag<float, 4> d4;
  TapsAheadOfReads(
      df, end, [&](int x) { NodeTaps(df, taps, row, x); },
      [&](int x, int x_end) {
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3  // two texels a vector
        for (int j = x; j < x_end; j += 2) NodeReadPair(slice, row, wS, j, j < row.single, sum);
#else
        for (int j = x; j < x_end; ++j) NodeRead(d4, slice, row, wS, j, j < row.single, sum[j]);
#endif
      });
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

SunCosineTapsFloat::SunCosineTapsFloat(const MuSAxis::Constants& c) {
  const double A = 1.0 / c.inv_A, span = 1.0 / c.inv_span;
  lo = float(std::max(-1.0, c.mu_s_min));
  h2 = float(c.H2 / c.rb2);
  k1 = float((A * span + c.d_min) / c.rb);
  ak2 = float(A * (span - c.d_min) / c.rb);
  ah2 = float(A * c.H2 / c.rb2);
  last = float(c.size - 1);
  below_last = float(c.size - 2);
}

// std::max(v, lo) is Max(lo, v) and std::min(v, hi) Min(hi, v) for every
// non-NaN v, signed zeros included: the lanes' operations.
void SunCosineTapsFloat::tap(double mu_s, int& i0, float& w) const {
  const float m = std::min(std::max(float(mu_s), lo), 1.0f);
  const float D = m + std::sqrt(m * m + h2);
  const float u = std::min(std::max(D * k1 - h2, 0.0f) / (D * ak2 + ah2), 1.0f);
  const float t = u * last;
  const float i = std::min(float(int(t)), below_last);
  w = t - i;
  i0 = int(i);
}


HWY_EXPORT(AddNodeSliceReads);

void add_node_slice_reads(const NodeRow& row, const SunCosineTapsFloat& taps, const Rgb4* slice,
                          const Rgb4& wS, int end, Rgb4* sum) {
  HWY_DYNAMIC_DISPATCH(AddNodeSliceReads)(row, taps, slice, wS, end, sum);
}

}  // namespace skybake
#endif  // HWY_ONCE

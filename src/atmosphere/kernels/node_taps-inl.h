// The taps every node of a multiple-scattering row takes, over a lane type
// (Highway; docs/architecture.md "Kernels"): the sun's cosine at the node
// for each texel and its mu_s tap (SunCosineTapsFloat::tap), shared by the
// reads over the 4D density (node_slice_reads.cpp) and over the density in
// the sun's frame (sun_frame_reads.cpp). The same IEEE operations as the
// one-lane functions, no FMA (-ffp-contract=off), so the same bits on
// every target.
//
// Included by a kernel's .cpp inside its per-target namespace (hwy/
// foreach_target.h), hence the toggled guard instead of #pragma once.
#if defined(SKYBAKE_ATMOSPHERE_KERNELS_NODE_TAPS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SKYBAKE_ATMOSPHERE_KERNELS_NODE_TAPS_INL_H_
#undef SKYBAKE_ATMOSPHERE_KERNELS_NODE_TAPS_INL_H_
#else
#define SKYBAKE_ATMOSPHERE_KERNELS_NODE_TAPS_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>

#include "atmosphere/kernels/node_slice_reads.hpp"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The cosines (r mu_s + s nu) / r_i of texels x .. x + Lanes(dd) - 1 in
// double (the product by 1 / r_i, not a division, as single scattering's
// SingleScatteringRay::at_suns).
template <class DD>
HWY_INLINE hn::Vec<DD> NodeCosines(DD dd, double r, double s, double inv_r_i,
                                   const double* mu_s, const double* nu, int x) {
  return hn::Mul(hn::Add(hn::Mul(hn::Set(dd, r), hn::LoadU(dd, mu_s + x)),
                         hn::Mul(hn::Set(dd, s), hn::LoadU(dd, nu + x))),
                 hn::Set(dd, inv_r_i));
}
// The same rounded to float, a full vector of them.
template <class DF>
HWY_INLINE hn::Vec<DF> NodeCosinesFloat(DF df, double r, double s, double inv_r_i,
                                        const double* mu_s, const double* nu, int x) {
#if HWY_TARGET == HWY_SCALAR  // one lane
  return hn::DemoteTo(df, NodeCosines(hn::Rebind<double, DF>(), r, s, inv_r_i, mu_s, nu, x));
#else  // a full vector of floats is twice the doubles'
  const hn::Half<DF> dh;
  const hn::Rebind<double, decltype(dh)> dd;
  return hn::Combine(df,
                     hn::DemoteTo(dh, NodeCosines(dd, r, s, inv_r_i, mu_s, nu,
                                                  x + int(hn::Lanes(dh)))),
                     hn::DemoteTo(dh, NodeCosines(dd, r, s, inv_r_i, mu_s, nu, x)));
#endif
}

// A whole number i of float lanes (|i| < 2^22) as int32: the low bits of
// i + 1.5 2^23, no conversion instructions (whose overflow checks Highway
// adds).
template <class DF>
HWY_INLINE hn::Vec<hn::Rebind<int32_t, DF>> WholeToInt(DF df, hn::Vec<DF> i) {
  const hn::Rebind<int32_t, DF> di;
  const hn::Vec<DF> magic = hn::Set(df, 0x1.8p23f);
  return hn::Sub(hn::BitCast(di, hn::Add(i, magic)), hn::BitCast(di, magic));
}

// SunCosineTapsFloat::tap of the cosines c: the texel (a whole float) and
// the weight of the next one.
template <class DF>
HWY_INLINE hn::Vec<DF> MuSTap(DF df, const SunCosineTapsFloat& k, hn::Vec<DF> c,
                              hn::Vec<DF>& weight) {
  using V = hn::Vec<DF>;
  const V one = hn::Set(df, 1.0f), h2 = hn::Set(df, k.h2);
  const V m = hn::Min(one, hn::Max(hn::Set(df, k.lo), c));
  const V D = hn::Add(m, hn::Sqrt(hn::Add(hn::Mul(m, m), h2)));
  const V N = hn::Max(hn::Zero(df), hn::Sub(hn::Mul(D, hn::Set(df, k.k1)), h2));
  const V Q = hn::Add(hn::Mul(D, hn::Set(df, k.ak2)), hn::Set(df, k.ah2));
  const V t = hn::Mul(hn::Min(one, hn::Div(N, Q)), hn::Set(df, k.last));
  // float(int(t)) is Trunc(t) + 0 (the sum turns a -0 into int's +0).
  const V i = hn::Min(hn::Set(df, k.below_last), hn::Add(hn::Trunc(t), hn::Zero(df)));
  weight = hn::Sub(t, i);
  return i;
}

// The loop of a node over texels [0, end): taps(x) for the group of
// Lanes(df) texels from x, kTapsAhead texels ahead of reads(x, x_end) for
// the group's texels, so that the reads do not wait on the divider's
// latency and the two overlap. Sixteen lanes: the taps of a last group may
// run past `end` (RowTexels' arrays hold 16 more texels) on valid texels;
// the reads do not.
constexpr int kTapsAhead = 16;
template <class DF, class Taps, class Reads>
HWY_INLINE void TapsAheadOfReads(DF df, int end, const Taps& taps, const Reads& reads) {
  const int step = int(hn::Lanes(df));
  for (int x = 0; x < std::min(kTapsAhead, end); x += step) taps(x);
  for (int x = 0; x < end; x += step) {
    if (x + kTapsAhead < end) taps(x + kTapsAhead);
    reads(x, std::min(x + step, end));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#endif  // include guard

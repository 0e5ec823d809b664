// The loop of one node of a multiple-scattering row over the density in
// the sun's frame, over lanes (Highway, every target from one source). See
// the header.
#include "atmosphere/kernels/sun_frame_reads.hpp"

#include <algorithm>
#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/sun_frame_reads.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/node_taps-inl.h"

#ifndef SKYBAKE_SUN_FRAME_READS_CONSTANTS  // once, not per target
#define SKYBAKE_SUN_FRAME_READS_CONSTANTS
namespace skybake {
namespace {
// Below this sin_nu sin_s the azimuth about the sun is undefined (the sun
// or the view at the zenith, or the view at the sun) and J does not depend
// on it: cos_phi = 1.
constexpr float kAzimuthFloor = 1e-6f;
// The divisor's floor, so that no lane divides by zero.
constexpr float kDivisorFloor = 1e-30f;
}  // namespace
}  // namespace skybake
#endif

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// sun_frame_tap of the texels from x.
template <class DF>
HWY_INLINE void Taps(DF df, const SunCosineTapsFloat& k, const SunFrameNode& q, int x) {
  using V = hn::Vec<DF>;
  const hn::Rebind<int32_t, DF> di;
  const V one = hn::Set(df, 1.0f), minus_one = hn::Set(df, -1.0f);
  const V cosine = NodeCosinesFloat(df, q.r, q.s, q.inv_r_i, q.mu_s, q.nu, x);
  V lw;
  const V l = MuSTap(df, k, cosine, lw);
  hn::StoreU(lw, df, q.lw + x);
  // cos_phi = (mu_i - nu mu_s) / (sin_nu sin_s) (sun_frame_density.hpp).
  const V g = hn::Min(one, hn::Max(minus_one, cosine));
  const V sin_s = hn::Sqrt(hn::Max(hn::Zero(df), hn::Sub(one, hn::Mul(g, g))));
  const V den = hn::Mul(hn::LoadU(df, q.sin_nu + x), sin_s);
  const V num = hn::Sub(hn::Set(df, q.mu_i), hn::Mul(hn::LoadU(df, q.nu_f + x), g));
  const V quotient = hn::Div(num, hn::Max(hn::Set(df, kDivisorFloor), den));
  const V c = hn::Min(
      one, hn::Max(minus_one, hn::IfThenElse(hn::Gt(den, hn::Set(df, kAzimuthFloor)), quotient,
                                             one)));
  const V t = hn::Mul(hn::Sub(one, c), hn::Set(df, 0.5f * float(q.phi_size - 1)));
  const V p = hn::Min(hn::Set(df, float(q.phi_size - 2)), hn::Add(hn::Trunc(t), hn::Zero(df)));
  hn::StoreU(hn::Sub(t, p), df, q.pw + x);
  const auto P = hn::Set(di, q.phi_size);
  const auto li = WholeToInt(df, l), pi = WholeToInt(df, p);
  hn::StoreU(hn::Add(hn::Mul(hn::Add(hn::LoadU(di, q.nu_i0 + x), li), P), pi), di, q.at0 + x);
  hn::StoreU(hn::Add(hn::Mul(hn::Add(hn::LoadU(di, q.nu_i1 + x), li), P), pi), di, q.at1 + x);
}

// (1 - w) a + w b of two texels, Lanes(d4) channels from c.
template <class D4>
HWY_INLINE hn::Vec<D4> Lerp(D4 d4, hn::Vec<D4> a, hn::Vec<D4> b, hn::Vec<D4> w0,
                            hn::Vec<D4> w1) {
  return hn::Add(hn::Mul(w0, a), hn::Mul(w1, b));
}

// The trilinear read (r, mu_s, cos_phi) of one slice from its first texel
// `at`, channels from c.
template <class D4>
HWY_INLINE hn::Vec<D4> SliceRead(D4 d4, const Rgb4* r0, const Rgb4* r1, int at, int P, size_t c,
                                 const hn::Vec<D4> w[6]) {
  auto phi = [&](const Rgb4* t) {
    return Lerp(d4, hn::LoadU(d4, t[0].v + c), hn::LoadU(d4, t[1].v + c), w[4], w[5]);
  };
  const auto a = Lerp(d4, phi(r0 + at), phi(r0 + at + P), w[2], w[3]);
  const auto b = Lerp(d4, phi(r1 + at), phi(r1 + at + P), w[2], w[3]);
  return Lerp(d4, a, b, w[0], w[1]);
}

// sum += wS sun_frame_read(x).
template <class D4>
HWY_INLINE void Read(D4 d4, const SunFrameNode& q, const Rgb4* r0, const Rgb4* r1, float rw,
                     const Rgb4& wS, int x, bool one_slice, Rgb4& sum) {
  using V = hn::Vec<D4>;
  const float lw = q.lw[x], pw = q.pw[x], nw = q.nu_w[x];
  const V w[6] = {hn::Set(d4, 1.0f - rw), hn::Set(d4, rw), hn::Set(d4, 1.0f - lw),
                  hn::Set(d4, lw),        hn::Set(d4, 1.0f - pw), hn::Set(d4, pw)};
  for (size_t c = 0; c < 4; c += hn::Lanes(d4)) {
    V L = SliceRead(d4, r0, r1, q.at0[x], q.phi_size, c, w);
    if (!one_slice)
      L = Lerp(d4, L, SliceRead(d4, r0, r1, q.at1[x], q.phi_size, c, w), hn::Set(d4, 1.0f - nw),
               hn::Set(d4, nw));
    hn::StoreU(hn::Add(hn::LoadU(d4, sum.v + c), hn::Mul(hn::LoadU(d4, wS.v + c), L)), d4,
               sum.v + c);
  }
}

}  // namespace

// On local copies of the constants (node_slice_reads.cpp).
void AddSunFrameReads(const SunFrameNode& q_in, const SunCosineTapsFloat& taps_in,
                      const Rgb4* r0, const Rgb4* r1, float rw, const Rgb4& wS_in, int end,
                      Rgb4* sum) {
  const SunFrameNode q = q_in;
  const SunCosineTapsFloat taps = taps_in;
  const Rgb4 wS = wS_in;
  const hn::ScalableTag<float> df;
  const hn::CappedTag<float, 4> d4;
  TapsAheadOfReads(
      df, end, [&](int x) { Taps(df, taps, q, x); },
      [&](int x, int x_end) {
        for (int j = x; j < x_end; ++j) Read(d4, q, r0, r1, rw, wS, j, j < q.single, sum[j]);
      });
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

// The lanes' operations one at a time: std::max(v, lo) is Max(lo, v) and
// std::min(v, hi) Min(hi, v) for every non-NaN v, signed zeros included.
void sun_frame_tap(const SunFrameNode& q, const SunCosineTapsFloat& taps, int x, int& at0,
                   int& at1, float& lw, float& pw) {
  const float cosine = float((q.r * q.mu_s[x] + q.s * q.nu[x]) * q.inv_r_i);
  int l = 0;
  taps.tap(cosine, l, lw);
  const float g = std::min(std::max(cosine, -1.0f), 1.0f);
  const float sin_s = std::sqrt(std::max(1.0f - g * g, 0.0f));
  const float den = q.sin_nu[x] * sin_s;
  const float quotient = (q.mu_i - q.nu_f[x] * g) / std::max(den, kDivisorFloor);
  const float c = std::min(std::max(den > kAzimuthFloor ? quotient : 1.0f, -1.0f), 1.0f);
  const float t = (1.0f - c) * (0.5f * float(q.phi_size - 1));
  const float p = std::min(float(int(t)), float(q.phi_size - 2));
  pw = t - p;
  at0 = (q.nu_i0[x] + l) * q.phi_size + int(p);
  at1 = (q.nu_i1[x] + l) * q.phi_size + int(p);
}

Rgb4 sun_frame_read(const SunFrameNode& q, const Rgb4* r0, const Rgb4* r1, float rw, int x) {
  auto lerp = [](float a, float b, float w) { return (1.0f - w) * a + w * b; };
  const int P = q.phi_size;
  const float lw = q.lw[x], pw = q.pw[x];
  auto slice = [&](int at, int c) {
    auto phi = [&](const Rgb4* t) { return lerp(t[0].v[c], t[1].v[c], pw); };
    return lerp(lerp(phi(r0 + at), phi(r0 + at + P), lw), lerp(phi(r1 + at), phi(r1 + at + P), lw),
                rw);
  };
  Rgb4 out;
  for (int c = 0; c < 4; ++c) {
    out.v[c] = slice(q.at0[x], c);
    if (x >= q.single) out.v[c] = lerp(out.v[c], slice(q.at1[x], c), q.nu_w[x]);
  }
  return out;
}

HWY_EXPORT(AddSunFrameReads);

void add_sun_frame_reads(const SunFrameNode& q, const SunCosineTapsFloat& taps, const Rgb4* r0,
                         const Rgb4* r1, float rw, const Rgb4& wS, int end, Rgb4* sum) {
  HWY_DYNAMIC_DISPATCH(AddSunFrameReads)(q, taps, r0, r1, rw, wS, end, sum);
}

}  // namespace skybake
#endif  // HWY_ONCE

// The table reads of the bakers' lane-wide loops, written once over a lane
// type (Highway; docs/architecture.md "Kernels"): sample_bilinear_rgb and
// lookup_sun_transmittance (transmittance_lut.hpp, Bruneton 2017
// GetTransmittanceToSun without the disk) in every lane, the same IEEE
// operations on the same operands in the same order as the one-value
// functions, no FMA (the kernels are built with -ffp-contract=off), so the
// same bits on every target. std::clamp(v, lo, hi) is Min(hi, Max(lo, v))
// and std::max(0.0, v) is Max(v, 0) for every non-NaN v, signed zeros
// included. Texel reads gather the same floats and widen them to double as
// the one-value read does.
//
// Included by a kernel's .cpp inside its per-target namespace (hwy/
// foreach_target.h), hence the toggled guard instead of #pragma once.
#if defined(SKYBAKE_ATMOSPHERE_KERNELS_TABLE_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SKYBAKE_ATMOSPHERE_KERNELS_TABLE_LANES_INL_H_
#undef SKYBAKE_ATMOSPHERE_KERNELS_TABLE_LANES_INL_H_
#else
#define SKYBAKE_ATMOSPHERE_KERNELS_TABLE_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

#include "atmosphere/medium.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "core/texture.hpp"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class D>
using Lanes = hn::Vec<D>;
// Texel offsets (in floats) of the lanes of D.
template <class D>
using Offsets = hn::Vec<hn::Rebind<int32_t, D>>;

// std::clamp(v, lo, hi) in each lane.
template <class D>
HWY_INLINE Lanes<D> ClampLanes(D d, Lanes<D> v, double lo, double hi) {
  return hn::Min(hn::Set(d, hi), hn::Max(hn::Set(d, lo), v));
}

// values[first .. first + count) in the lanes, count in [1, Lanes(d)]; a
// short group repeats its last value in the spare lanes.
template <class D>
HWY_INLINE Lanes<D> LoadGroup(D d, const double* values, size_t first, size_t count) {
  const size_t n = hn::Lanes(d);
  if (count == n) return hn::LoadU(d, values + first);
  HWY_ALIGN double lanes[hn::MaxLanes(d)];
  for (size_t j = 0; j < n; ++j) lanes[j] = values[first + std::min(j, count - 1)];
  return hn::Load(d, lanes);
}

// texel_coord_from_unit(x, n) in each lane.
template <class D>
HWY_INLINE Lanes<D> TexelCoord(D d, Lanes<D> x, int n) {
  return hn::Add(hn::Set(d, 0.5 / n), hn::Mul(x, hn::Set(d, 1.0 - 1.0 / n)));
}

// bilinear_axis(u, width, false) in each lane: the texel indices times
// `stride` (offsets in floats) and the weight of the second; a coordinate
// that is not finite reads texel 0.
template <class D>
struct AxisLanes {
  Offsets<D> o0, o1;
  Lanes<D> f;
};
template <class D>
HWY_INLINE AxisLanes<D> AxisAt(D d, int width, int stride, Lanes<D> u) {
  const hn::Rebind<int32_t, D> di;
  Lanes<D> x = hn::Sub(hn::Mul(u, hn::Set(d, double(width))), hn::Set(d, 0.5));
  x = hn::IfThenElseZero(hn::Eq(hn::Sub(x, x), hn::Zero(d)), x);
  x = ClampLanes(d, x, 0.0, double(width - 1));
  const Lanes<D> x0 = hn::Floor(x);
  const Offsets<D> i0 = hn::DemoteTo(di, x0);
  const Offsets<D> i1 = hn::Min(hn::Add(i0, hn::Set(di, 1)), hn::Set(di, width - 1));
  return {hn::Mul(i0, hn::Set(di, stride)), hn::Mul(i1, hn::Set(di, stride)), hn::Sub(x, x0)};
}

// Where a bilinear read of three channels falls in each lane: the four
// texels' offsets, the weights along the row (fx) and across rows (fy), and
// the lanes that read 0 instead (the one-value read's early +0).
template <class D>
struct TexelQuad {
  Offsets<D> o00, o10, o01, o11;
  Lanes<D> fx, fy;
  hn::Mask<D> zero;
};

template <class D>
struct RgbLanes {
  Lanes<D> c[3];
};

// sample_bilinear_rgb's operations on the quad's texels, lane by lane.
template <class D>
HWY_INLINE RgbLanes<D> ReadRgb(D d, const float* data, const TexelQuad<D>& q) {
  const hn::Rebind<float, D> df;
  RgbLanes<D> out;
  if (hn::AllTrue(d, q.zero)) {  // no load where every lane reads 0
    for (Lanes<D>& c : out.c) c = hn::Zero(d);
    return out;
  }
  for (int c = 0; c < 3; ++c) {
    const Lanes<D> t00 = hn::PromoteTo(d, hn::GatherIndex(df, data + c, q.o00));
    const Lanes<D> t10 = hn::PromoteTo(d, hn::GatherIndex(df, data + c, q.o10));
    const Lanes<D> t01 = hn::PromoteTo(d, hn::GatherIndex(df, data + c, q.o01));
    const Lanes<D> t11 = hn::PromoteTo(d, hn::GatherIndex(df, data + c, q.o11));
    const Lanes<D> lo = hn::Add(t00, hn::Mul(q.fx, hn::Sub(t10, t00)));
    const Lanes<D> hi = hn::Add(t01, hn::Mul(q.fx, hn::Sub(t11, t01)));
    out.c[c] = hn::IfThenZeroElse(q.zero, hn::Add(lo, hn::Mul(q.fy, hn::Sub(hi, lo))));
  }
  return out;
}

// The quad of a read at texel coordinates (u, v) of a whole table.
template <class D>
HWY_INLINE TexelQuad<D> TableQuad(D d, const Texture& tex, Lanes<D> u, Lanes<D> v) {
  const int channels = tex.channel_count();
  const AxisLanes<D> ax = AxisAt(d, tex.width, channels, u);
  const AxisLanes<D> ay = AxisAt(d, tex.height, tex.width * channels, v);
  return {hn::Add(ay.o0, ax.o0), hn::Add(ay.o0, ax.o1), hn::Add(ay.o1, ax.o0),
          hn::Add(ay.o1, ax.o1), ax.f,                  ay.f,
          hn::FirstN(d, 0)};
}

// The quad of a read along u of one row pair of `tex` (a lookup at one
// radius: sample_bilinear_rgb(tex, row, u)).
template <class D>
HWY_INLINE TexelQuad<D> RowQuad(D d, const Texture& tex, const BilinearRow& row, Lanes<D> u) {
  const hn::Rebind<int32_t, D> di;
  const Offsets<D> row0 = hn::Set(di, int32_t(row.row0 - tex.data.data()));
  const Offsets<D> row1 = hn::Set(di, int32_t(row.row1 - tex.data.data()));
  const AxisLanes<D> ax = AxisAt(d, tex.width, row.channels, u);
  return {hn::Add(row0, ax.o0), hn::Add(row0, ax.o1), hn::Add(row1, ax.o0),
          hn::Add(row1, ax.o1), ax.f,                 hn::Set(d, row.fy),
          hn::FirstN(d, 0)};
}

// transmittance_at_radius in each lane: the radius clamped to the shell,
// the mapping's distance range at it and the table's rows around v(r).
template <class D>
struct RadiusLanes {
  Lanes<D> r, d_min, span, fy;  // span: d_max - d_min
  Offsets<D> row0, row1;
};
template <class D>
HWY_INLINE RadiusLanes<D> RadiusAt(D d, const Texture& lut, const Atmosphere& atm,
                                   Lanes<D> radius) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double horizon = safe_sqrt((rt - rb) * (rt + rb));  // horizon_distance
  RadiusLanes<D> l;
  l.r = ClampLanes(d, radius, rb, rt);
  const Lanes<D> rho = hn::Sqrt(hn::Max(
      hn::Zero(d), hn::Mul(hn::Sub(l.r, hn::Set(d, rb)), hn::Add(l.r, hn::Set(d, rb)))));
  const Lanes<D> v = TexelCoord(d, hn::Div(rho, hn::Set(d, horizon)), lut.height);
  const AxisLanes<D> ay = AxisAt(d, lut.height, lut.width * lut.channel_count(), v);
  l.row0 = ay.o0;
  l.row1 = ay.o1;
  l.fy = ay.f;
  l.d_min = hn::Sub(hn::Set(d, rt), l.r);
  l.span = hn::Sub(hn::Add(rho, hn::Set(d, horizon)), l.d_min);
  return l;
}

// The same from one radius's transmittance_at_radius, in every lane.
template <class D>
HWY_INLINE RadiusLanes<D> RadiusAt(D d, const Texture& lut, const TransmittanceAtRadius& at) {
  const hn::Rebind<int32_t, D> di;
  const float* data = lut.data.data();
  return {hn::Set(d, at.r),
          hn::Set(d, at.d_min),
          hn::Set(d, at.d_max - at.d_min),
          hn::Set(d, at.row.fy),
          hn::Set(di, int32_t(at.row.row0 - data)),
          hn::Set(di, int32_t(at.row.row1 - data))};
}

// lookup_sun_transmittance(lut, at, Rb, mu)'s quad in each lane, mu already
// clamped to [-1, 1]; `zero` marks Vis = 0 (the sun below the horizon).
template <class D>
HWY_INLINE TexelQuad<D> SunQuad(D d, const Texture& lut, const Atmosphere& atm,
                                const RadiusLanes<D>& at, Lanes<D> mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const Lanes<D> zero = hn::Zero(d);
  const Lanes<D> rr_mm1 = hn::Mul(hn::Mul(at.r, at.r), hn::Sub(hn::Mul(mu, mu), hn::Set(d, 1.0)));
  const hn::Mask<D> ground =
      hn::And(hn::Lt(mu, zero), hn::Ge(hn::Add(rr_mm1, hn::Set(d, rb * rb)), zero));
  const Lanes<D> d_top = hn::Max(  // distance_to_top_boundary
      hn::Add(hn::Mul(hn::Neg(at.r), mu),
              hn::Sqrt(hn::Max(zero, hn::Add(rr_mm1, hn::Set(d, rt * rt))))),
      zero);
  const Lanes<D> x_mu = ClampLanes(d, hn::Div(hn::Sub(d_top, at.d_min), at.span), 0.0, 1.0);
  const AxisLanes<D> ax = AxisAt(d, lut.width, lut.channel_count(),
                                       TexelCoord(d, x_mu, lut.width));
  return {hn::Add(at.row0, ax.o0), hn::Add(at.row0, ax.o1), hn::Add(at.row1, ax.o0),
          hn::Add(at.row1, ax.o1), ax.f,                    at.fy,
          ground};
}

// lookup_sun_transmittance(lut, at, Rb, mu) in each lane, mu clamped.
template <class D>
HWY_INLINE RgbLanes<D> SunTransmittance(D d, const Texture& lut, const Atmosphere& atm,
                                        const RadiusLanes<D>& at, Lanes<D> mu) {
  return ReadRgb(d, lut.data.data(), SunQuad(d, lut, atm, at, mu));
}

// Lanes [0, count) of three channels into out[0 .. count).
template <class D>
HWY_INLINE void StoreRgb(D d, const RgbLanes<D>& v, size_t count, glm::dvec3* out) {
  HWY_ALIGN double lanes[3][hn::MaxLanes(d)];
  for (int c = 0; c < 3; ++c) hn::Store(v.c[c], d, lanes[c]);
  for (size_t k = 0; k < count; ++k) out[k] = glm::dvec3(lanes[0][k], lanes[1][k], lanes[2][k]);
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#endif  // SKYBAKE_ATMOSPHERE_KERNELS_TABLE_LANES_INL_H_

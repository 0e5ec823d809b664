// The sun-angle taps over lanes (Highway, every target from one source): per
// lane the operations of MuSAxis::tap and of TransmittanceReader::to_sun in
// the same order on the same operands, so the same bits as one cosine at a
// time (tests/atmosphere/kernels_test.cpp). std::min(a, b) is Min(b, a) and
// std::max(a, b) is Max(b, a), signed zeros included, and std::clamp(v, lo,
// hi) is Min(hi, Max(lo, v)) for every non-NaN v.
#include "atmosphere/kernels/sun_taps.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/sun_taps.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/table_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace {

// Texel-centre taps of x in [0, 1] over n texels: i0 = min(int(t), n - 2),
// w = t - i0, t = x (n - 1).
template <class D>
struct TapLanes {
  Offsets<D> i0;
  Lanes<D> w;
};
template <class D>
HWY_INLINE TapLanes<D> Taps(D d, Lanes<D> x, int n_texels) {
  const hn::Rebind<int32_t, D> di;
  const Lanes<D> t = hn::Mul(x, hn::Set(d, double(n_texels - 1)));
  const Lanes<D> i = hn::Min(hn::Set(d, double(n_texels - 2)), hn::PromoteTo(d, hn::DemoteTo(di, t)));
  return {hn::DemoteTo(di, i), hn::Sub(t, i)};
}

// The first `count` lanes of v at out.
template <class D, typename T>
HWY_INLINE void StoreFirst(D d, hn::Vec<D> v, size_t count, T* out) {
  if (count == hn::Lanes(d)) return hn::StoreU(v, d, out);
  HWY_ALIGN T lanes[hn::MaxLanes(d)];
  hn::Store(v, d, lanes);
  std::copy(lanes, lanes + count, out);
}

// TransmittanceReader::to_sun of the lanes' cosines at the row; false
// (and nothing read) where the sun is below the horizon in every lane.
template <class D>
HWY_INLINE bool ToSun(D d, const SunTapTable& table, const TransmittanceReader::Row& row,
                      Lanes<D> raw, RgbLanes<D>& out) {
  const Lanes<D> zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const Lanes<D> mu = ClampLanes(d, raw, -1.0, 1.0);
  // distance_to_top_boundary, then to_top's x_mu.
  const Lanes<D> discriminant = hn::Add(
      hn::Mul(hn::Set(d, row.r * row.r), hn::Sub(hn::Mul(mu, mu), one)), hn::Set(d, table.rt * table.rt));
  const Lanes<D> d_top = hn::Max(
      hn::Add(hn::Mul(hn::Set(d, -row.r), mu), hn::Sqrt(hn::Max(zero, discriminant))), zero);
  const Lanes<D> x =
      ClampLanes(d, hn::Mul(hn::Sub(d_top, hn::Set(d, row.d_min)), hn::Set(d, row.inv_span)), 0.0, 1.0);
  const TapLanes<D> tap = Taps(d, x, table.width);
  // The sun's smoothstep: 1 at s >= 1, 0 at s <= 0.
  const Lanes<D> s = hn::Mul(hn::Sub(raw, hn::Set(d, row.sun_edge)), hn::Set(d, row.inv_sun_width));
  const Lanes<D> smooth =
      hn::Mul(hn::Mul(s, s), hn::Sub(hn::Set(d, 3.0), hn::Mul(hn::Set(d, 2.0), s)));
  const Lanes<D> visible =
      hn::IfThenElse(hn::Ge(s, one), one, hn::IfThenZeroElse(hn::Le(s, zero), smooth));
  // Below the horizon in every lane: T = 0 would add +0 to sums >= +0.
  if (hn::AllTrue(d, hn::Eq(visible, zero))) return false;
  const hn::Rebind<float, D> df;
  const hn::Rebind<int32_t, D> di;
  const Offsets<D> o0 = hn::Mul(tap.i0, hn::Set(di, table.stride));
  const Lanes<D> wy = hn::Set(d, row.wy);
  for (int c = 0; c < 3; ++c) {
    const Lanes<D> t00 = hn::PromoteTo(d, hn::GatherIndex(df, row.row0 + c, o0));
    const Lanes<D> t10 = hn::PromoteTo(d, hn::GatherIndex(df, row.row0 + table.stride + c, o0));
    const Lanes<D> t01 = hn::PromoteTo(d, hn::GatherIndex(df, row.row1 + c, o0));
    const Lanes<D> t11 = hn::PromoteTo(d, hn::GatherIndex(df, row.row1 + table.stride + c, o0));
    const Lanes<D> bottom = hn::Add(t00, hn::Mul(hn::Sub(t10, t00), tap.w));
    const Lanes<D> top = hn::Add(t01, hn::Mul(hn::Sub(t11, t01), tap.w));
    out.c[c] = hn::Mul(visible, hn::Add(bottom, hn::Mul(hn::Sub(top, bottom), wy)));
  }
  return true;
}

}  // namespace

void MuSTaps(const MuSAxis::Constants& c, const double* mu_s, int n, int* i0, double* w) {
  using D = hn::ScalableTag<double>;
  const D d;
  const hn::Rebind<int32_t, D> di;
  const size_t lanes = hn::Lanes(d);
  const Lanes<D> one = hn::Set(d, 1.0), zero = hn::Zero(d);
  for (size_t k = 0; k < size_t(n); k += lanes) {
    const size_t count = std::min(lanes, size_t(n) - k);
    const Lanes<D> m = ClampLanes(d, LoadGroup(d, mu_s, k, count), c.mu_s_min, 1.0);
    const Lanes<D> root = hn::Sqrt(
        hn::Max(zero, hn::Add(hn::Mul(hn::Mul(hn::Set(d, c.rb2), m), m), hn::Set(d, c.H2))));
    const Lanes<D> dist = hn::Add(hn::Mul(hn::Set(d, -c.rb), m), root);
    const Lanes<D> a = hn::Mul(hn::Sub(dist, hn::Set(d, c.d_min)), hn::Set(d, c.inv_span));
    const Lanes<D> x = hn::Div(hn::Max(zero, hn::Sub(one, hn::Mul(a, hn::Set(d, c.inv_A)))),
                               hn::Add(one, a));
    const TapLanes<D> t = Taps(d, ClampLanes(d, x, 0.0, 1.0), c.size);
    StoreFirst(di, t.i0, count, i0 + k);
    StoreFirst(d, t.w, count, w + k);
  }
}

void AddSunProducts(const SunTapTable& table, const TransmittanceReader::Row& row,
                    const double* mu_s, int n, const glm::dvec3& a_rayleigh,
                    const glm::dvec3& a_mie, double* const sums[6]) {
  using D = hn::ScalableTag<double>;
  const D d;
  const size_t lanes = hn::Lanes(d);
  const double a[6] = {a_rayleigh.r, a_rayleigh.g, a_rayleigh.b, a_mie.r, a_mie.g, a_mie.b};
  for (size_t k = 0; k < size_t(n); k += lanes) {
    const size_t count = std::min(lanes, size_t(n) - k);
    RgbLanes<D> T;
    if (!ToSun(d, table, row, LoadGroup(d, mu_s, k, count), T)) continue;
    for (int g = 0; g < 6; ++g) {
      const Lanes<D> sum = LoadGroup(d, sums[g], k, count);
      StoreFirst(d, hn::Add(sum, hn::Mul(hn::Set(d, a[g]), T.c[g % 3])), count, sums[g] + k);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(MuSTaps);
HWY_EXPORT(AddSunProducts);

void mu_s_taps(const MuSAxis::Constants& c, const double* mu_s, int n, int* i0, double* w) {
  HWY_DYNAMIC_DISPATCH(MuSTaps)(c, mu_s, n, i0, w);
}

void add_sun_products(const SunTapTable& table, const TransmittanceReader::Row& row,
                      const double* mu_s, int n, const glm::dvec3& a_rayleigh,
                      const glm::dvec3& a_mie, double* const sums[6]) {
  HWY_DYNAMIC_DISPATCH(AddSunProducts)(table, row, mu_s, n, a_rayleigh, a_mie, sums);
}

}  // namespace skybake
#endif  // HWY_ONCE

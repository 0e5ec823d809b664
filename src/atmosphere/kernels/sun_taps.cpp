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

// The row's constants of both passes, broadcast once per call: read
// through the arguments in the loops, they were loaded again after every
// store (the stores might have changed them).
template <class D>
struct SunRowLanes {
  Lanes<D> minus_r, rr, tt, d_min, inv_span, last, below_last, edge, inv_width, wy;
  const float *row0, *row1;
  int stride;
  SunRowLanes(D d, const SunTapTable& table, const TransmittanceReader::Row& row)
      : minus_r(hn::Set(d, -row.r)),
        rr(hn::Set(d, row.r * row.r)),
        tt(hn::Set(d, table.rt * table.rt)),
        d_min(hn::Set(d, row.d_min)),
        inv_span(hn::Set(d, row.inv_span)),
        last(hn::Set(d, double(table.width - 1))),
        below_last(hn::Set(d, double(table.width - 2))),
        edge(hn::Set(d, row.sun_edge)),
        inv_width(hn::Set(d, row.inv_sun_width)),
        wy(hn::Set(d, row.wy)),
        row0(row.row0),
        row1(row.row1),
        stride(table.stride) {}
};

// The suns' zenith cosines at the node (NodeSuns): std::min(std::max(v,
// -1), 1) is ClampLanes(v, -1, 1).
template <class D>
struct NodeSunLanes {
  Lanes<D> r, s, inv_r;
  NodeSunLanes(D d, const NodeSuns& suns)
      : r(hn::Set(d, suns.r)), s(hn::Set(d, suns.s)), inv_r(hn::Set(d, suns.inv_r)) {}
  Lanes<D> mu_s(D d, Lanes<D> mu_s_start, Lanes<D> nu) const {
    return ClampLanes(d, hn::Mul(hn::Add(hn::Mul(r, mu_s_start), hn::Mul(s, nu)), inv_r), -1.0, 1.0);
  }
};

// The first pass of TransmittanceReader::to_sun for the lanes' cosines at
// the row: the table's column i0, the weight w and the sun's visible
// fraction. Taps' operations, on the hoisted constants.
template <class D>
HWY_INLINE void SunTaps(D d, const SunRowLanes<D>& q, Lanes<D> raw, int32_t* i0, double* w,
                        double* visible) {
  const hn::Rebind<int32_t, D> di;
  const Lanes<D> zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const Lanes<D> mu = ClampLanes(d, raw, -1.0, 1.0);
  // distance_to_top_boundary, then to_top's x_mu.
  const Lanes<D> discriminant = hn::Add(hn::Mul(q.rr, hn::Sub(hn::Mul(mu, mu), one)), q.tt);
  const Lanes<D> d_top =
      hn::Max(hn::Add(hn::Mul(q.minus_r, mu), hn::Sqrt(hn::Max(zero, discriminant))), zero);
  const Lanes<D> x = ClampLanes(d, hn::Mul(hn::Sub(d_top, q.d_min), q.inv_span), 0.0, 1.0);
  const Lanes<D> t = hn::Mul(x, q.last);
  const Lanes<D> i = hn::Min(q.below_last, hn::PromoteTo(d, hn::DemoteTo(di, t)));
  hn::StoreU(hn::DemoteTo(di, i), di, i0);
  hn::StoreU(hn::Sub(t, i), d, w);
  // The sun's smoothstep: 1 at s >= 1, 0 at s <= 0.
  const Lanes<D> s = hn::Mul(hn::Sub(raw, q.edge), q.inv_width);
  const Lanes<D> smooth =
      hn::Mul(hn::Mul(s, s), hn::Sub(hn::Set(d, 3.0), hn::Mul(hn::Set(d, 2.0), s)));
  hn::StoreU(hn::IfThenElse(hn::Ge(s, one), one, hn::IfThenZeroElse(hn::Le(s, zero), smooth)), d,
             visible);
}

// R, G, B of the texels i0 and i0 + 1 of `row`, one lane each, widened to
// double. With four lanes (AVX2, AVX-512 at four) a lane's two texels are
// two 128-bit loads, R G B at positions 0-2 of a load at the first and 1-3
// of a load ending at the second's blue (any stride >= 3, never past the
// row), transposed into lanes. Elsewhere (SSE4, the scalar target) each
// lane's six floats are read one by one: those targets have no gather
// instruction, and the emulated gather (a store and a load per lane and
// channel) took several times longer. Native gathers were slower than
// either.
template <class D>
HWY_INLINE void TexelPairs(D d, int stride, const float* row, const int32_t* i0,
                           Lanes<D> out[2][3]) {
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3
  const hn::Full128<float> d4;
  auto transpose = [&](int shift, hn::Vec<decltype(d4)> c[4]) {
    hn::Vec<decltype(d4)> r[4];
    for (int l = 0; l < 4; ++l) r[l] = hn::LoadU(d4, row + stride * i0[l] + shift);
    const auto t0 = hn::InterleaveLower(d4, r[0], r[1]), t1 = hn::InterleaveLower(d4, r[2], r[3]);
    const auto t2 = hn::InterleaveUpper(d4, r[0], r[1]), t3 = hn::InterleaveUpper(d4, r[2], r[3]);
    c[0] = hn::ConcatLowerLower(d4, t1, t0);
    c[1] = hn::ConcatUpperUpper(d4, t1, t0);
    c[2] = hn::ConcatLowerLower(d4, t3, t2);
    c[3] = hn::ConcatUpperUpper(d4, t3, t2);
  };
  hn::Vec<decltype(d4)> lo[4], hi[4];
  transpose(0, lo);
  transpose(stride - 1, hi);
  HWY_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    out[0][c] = hn::PromoteTo(d, lo[c]);
    out[1][c] = hn::PromoteTo(d, hi[c + 1]);
  }
#else
  // float to double is exact: the same values as PromoteTo.
  constexpr size_t kMax = hn::MaxLanes(d);
  HWY_ALIGN double texels[2][3][kMax];
  for (size_t l = 0; l < hn::Lanes(d); ++l) {
    const float* t = row + stride * i0[l];
    for (int c = 0; c < 3; ++c) {
      texels[0][c][l] = t[c];
      texels[1][c][l] = t[stride + c];
    }
  }
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) out[k][c] = hn::Load(d, texels[k][c]);
#endif
}

// After the taps: T = visible (bottom + (top - bottom) wy), the reads of
// to_top; false (and nothing read) where the sun is below the horizon in
// every lane.
template <class D>
HWY_INLINE bool SunReads(D d, const SunRowLanes<D>& q, const int32_t* i0_lanes,
                         const double* w_lanes, const double* visible_lanes, RgbLanes<D>& out) {
  const Lanes<D> visible = hn::LoadU(d, visible_lanes);
  // Below the horizon in every lane: T = 0 would add +0 to sums >= +0.
  if (hn::AllTrue(d, hn::Eq(visible, hn::Zero(d)))) return false;
  const Lanes<D> w = hn::LoadU(d, w_lanes);
  Lanes<D> t[2][2][3];  // [row][texel i0, i0 + 1][channel]
  TexelPairs(d, q.stride, q.row0, i0_lanes, t[0]);
  TexelPairs(d, q.stride, q.row1, i0_lanes, t[1]);
  HWY_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    const Lanes<D> bottom = hn::Add(t[0][0][c], hn::Mul(hn::Sub(t[0][1][c], t[0][0][c]), w));
    const Lanes<D> top = hn::Add(t[1][0][c], hn::Mul(hn::Sub(t[1][1][c], t[1][0][c]), w));
    out.c[c] = hn::Mul(visible, hn::Add(bottom, hn::Mul(hn::Sub(top, bottom), q.wy)));
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

// Every sun's taps and visible fraction first (the square roots), then the
// reads: in one loop each read waited on its square root's latency. The
// work arrays hold n rounded up to whole groups; whole groups go through
// loops without the short group's checks.
void AddSunProducts(const SunTapTable& table, const TransmittanceReader::Row& row,
                    const NodeSuns& suns, int n, const glm::dvec3& a_rayleigh,
                    const glm::dvec3& a_mie, double* const sums[6], SunTapScratch& scratch) {
  // At most four lanes: the texels' loads and transpose (TexelPairs) were
  // faster than gathers of eight.
  using D = hn::CappedTag<double, 4>;
  const D d;
  const size_t lanes = hn::Lanes(d), padded = (size_t(n) + lanes - 1) / lanes * lanes;
  const size_t whole = size_t(n) / lanes * lanes;
  scratch.i0.resize(padded);
  scratch.w.resize(padded);
  scratch.visible.resize(padded);
  int32_t* const i0 = scratch.i0.data();
  double* const w = scratch.w.data();
  double* const visible = scratch.visible.data();
  const SunRowLanes<D> q(d, table, row);
  const NodeSunLanes<D> at(d, suns);
  for (size_t k = 0; k < whole; k += lanes)
    SunTaps(d, q, at.mu_s(d, hn::LoadU(d, suns.mu_s + k), hn::LoadU(d, suns.nu + k)), i0 + k,
            w + k, visible + k);
  if (whole < size_t(n)) {
    const size_t count = size_t(n) - whole;
    SunTaps(d, q,
            at.mu_s(d, LoadGroup(d, suns.mu_s, whole, count), LoadGroup(d, suns.nu, whole, count)),
            i0 + whole, w + whole, visible + whole);
  }
  Lanes<D> a[6];
  const double a_values[6] = {a_rayleigh.r, a_rayleigh.g, a_rayleigh.b, a_mie.r, a_mie.g, a_mie.b};
  for (int c = 0; c < 6; ++c) a[c] = hn::Set(d, a_values[c]);
  double* const out[6] = {sums[0], sums[1], sums[2], sums[3], sums[4], sums[5]};
  for (size_t k = 0; k < whole; k += lanes) {
    RgbLanes<D> T;
    if (!SunReads(d, q, i0 + k, w + k, visible + k, T)) continue;
    HWY_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      hn::StoreU(hn::Add(hn::LoadU(d, out[c] + k), hn::Mul(a[c], T.c[c])), d, out[c] + k);
      hn::StoreU(hn::Add(hn::LoadU(d, out[3 + c] + k), hn::Mul(a[3 + c], T.c[c])), d,
                 out[3 + c] + k);
    }
  }
  RgbLanes<D> T;
  if (whole == size_t(n) || !SunReads(d, q, i0 + whole, w + whole, visible + whole, T)) return;
  const size_t count = size_t(n) - whole;
  for (int c = 0; c < 6; ++c)
    StoreFirst(d, hn::Add(LoadGroup(d, out[c], whole, count), hn::Mul(a[c], T.c[c % 3])), count,
               out[c] + whole);
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
                      const NodeSuns& suns, int n, const glm::dvec3& a_rayleigh,
                      const glm::dvec3& a_mie, double* const sums[6], SunTapScratch& scratch) {
  HWY_DYNAMIC_DISPATCH(AddSunProducts)(table, row, suns, n, a_rayleigh, a_mie, sums, scratch);
}

}  // namespace skybake
#endif  // HWY_ONCE

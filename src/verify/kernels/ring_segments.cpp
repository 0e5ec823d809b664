// ring_segment_terms over lanes (Highway, every target from one source):
// per lane ring_segment_term's operations on the same operands in the same
// order, std::max(a, b) as a < b ? b : a, so the same bits on every target
// (tests/verify/kernels_test.cpp). See the header.
#include "verify/kernels/ring_segments.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "verify/kernels/ring_segments.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// std::max(a, b) in each lane, NaN and signed zeros alike.
template <class V>
HWY_INLINE V MaxAsStdMax(V a, V b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

// The ray's constants: 2 r mu and r r as radius_after groups them, Rb.
struct RingRay {
  double two_r_mu, r2, bottom_m;
};

// Where segments [i, i + Lanes(d)) are lit: weight_centroid, then
// radius_after and the clamp to Rb.
template <class D>
HWY_INLINE void LitLanes(D d, size_t i, hn::Vec<D> start, hn::Vec<D> dt, hn::Vec<D> mean_sum,
                         hn::Vec<D> expm1_x, const RingRay& ray, RingSegmentTerms& out) {
  const hn::Vec<D> one = hn::Set(d, 1.0), zero = hn::Zero(d);
  const hn::Vec<D> x = hn::Mul(hn::Div(mean_sum, hn::Set(d, 3.0)), dt);
  const hn::Vec<D> thin = hn::Sub(hn::Set(d, 0.5), hn::Div(x, hn::Set(d, 12.0)));
  const hn::Vec<D> thick = hn::Sub(hn::Div(one, x), hn::Div(one, expm1_x));
  const hn::Vec<D> fraction = hn::IfThenElse(hn::Lt(x, hn::Set(d, 1e-4)), thin, thick);
  const hn::Vec<D> lit_at = hn::Add(start, hn::Mul(fraction, dt));
  const hn::Vec<D> q = hn::Add(
      hn::Add(hn::Mul(lit_at, lit_at), hn::Mul(hn::Set(d, ray.two_r_mu), lit_at)),
      hn::Set(d, ray.r2));
  const hn::Vec<D> radius =
      MaxAsStdMax(hn::Sqrt(MaxAsStdMax(q, zero)), hn::Set(d, ray.bottom_m));
  hn::StoreU(lit_at, d, out.lit_at.data() + i);
  hn::StoreU(radius, d, out.lit_radius.data() + i);
  hn::StoreU(hn::Div(one, radius), d, out.inverse_radius.data() + i);
}

// The terms of segments [i, i + Lanes(d)): the three channels' extinctions
// and the four expm1s of each segment de-interleaved, one per vector.
template <class D>
HWY_INLINE void SegmentLanes(D d, const double* ends, size_t i, const glm::dvec3* extinction,
                             const double* expm1s, const RingRay& ray, RingSegmentTerms& out) {
  const hn::Vec<D> start = hn::LoadU(d, ends + i);
  const hn::Vec<D> dt = hn::Sub(hn::LoadU(d, ends + i + 1), start);
  hn::Vec<D> em[4], e[3];
  hn::LoadInterleaved4(d, expm1s + 4 * i, em[0], em[1], em[2], em[3]);
  hn::LoadInterleaved3(d, &extinction[i].x, e[0], e[1], e[2]);
  for (int c = 0; c < 3; ++c) {  // segment_weights_from_expm1
    const hn::Vec<D> w = hn::Div(hn::Neg(em[c]), e[c]);
    hn::StoreU(hn::IfThenElse(hn::Gt(e[c], hn::Zero(d)), w, dt), d, out.weight[c].data() + i);
  }
  LitLanes(d, i, start, dt, hn::Add(hn::Add(e[0], e[1]), e[2]), em[3], ray, out);
}

// Whole vectors, then the rest one lane at a time.
void SegmentTermsOfRing(const double* ends, size_t n, const glm::dvec3* extinction,
                       const double* expm1s, double r, double mu, double bottom_m,
                       RingSegmentTerms& out) {
  const RingRay ray{2.0 * r * mu, r * r, bottom_m};
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  size_t i = 0;
  for (; i + hn::Lanes(d) <= n; i += hn::Lanes(d))
    SegmentLanes(d, ends, i, extinction, expm1s, ray, out);
  for (; i < n; ++i) SegmentLanes(d1, ends, i, extinction, expm1s, ray, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

// The lanes read a segment's extinction as three packed doubles.
static_assert(sizeof(glm::dvec3) == 3 * sizeof(double), "glm::dvec3 is three packed doubles");

HWY_EXPORT(SegmentTermsOfRing);

void ring_segment_terms(const double* ends, size_t n, const glm::dvec3* extinction,
                        const double* expm1s, double r, double mu, double bottom_m,
                        RingSegmentTerms& out) {
  for (std::vector<double>* v : {&out.weight[0], &out.weight[1], &out.weight[2], &out.lit_at,
                                 &out.lit_radius, &out.inverse_radius})
    v->resize(n);
  HWY_DYNAMIC_DISPATCH(SegmentTermsOfRing)(ends, n, extinction, expm1s, r, mu, bottom_m, out);
}

}  // namespace skybake
#endif  // HWY_ONCE

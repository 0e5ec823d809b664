// The node altitudes over lanes (Highway, every target from one source):
// per lane node_altitude_from_perigee's operations on the same operands (a
// square root is correctly rounded at any width), so the same bits on
// every target (tests/atmosphere/kernels_test.cpp). See the header.
#include "atmosphere/kernels/node_altitudes.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/node_altitudes.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Nodes [j, j + Lanes(d)).
template <class D>
HWY_INLINE void AltitudeLanes(D d, double* s, size_t j, hn::Vec<D> from_perigee, hn::Vec<D> p2,
                              hn::Vec<D> bottom_radius) {
  const hn::Vec<D> x_p = hn::Add(hn::LoadU(d, s + j), from_perigee);
  hn::StoreU(hn::Sub(hn::Sqrt(hn::Add(hn::Mul(x_p, x_p), p2)), bottom_radius), d, s + j);
}

// Whole vectors, then the rest one lane at a time.
void AltitudesFromPerigee(double* s, size_t n, double from_perigee, double p2,
                          double bottom_radius) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  size_t j = 0;
  for (; j + hn::Lanes(d) <= n; j += hn::Lanes(d))
    AltitudeLanes(d, s, j, hn::Set(d, from_perigee), hn::Set(d, p2), hn::Set(d, bottom_radius));
  for (; j < n; ++j)
    AltitudeLanes(d1, s, j, hn::Set(d1, from_perigee), hn::Set(d1, p2),
                  hn::Set(d1, bottom_radius));
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(AltitudesFromPerigee);

void altitudes_from_perigee(double* s, size_t n, double from_perigee, double p2,
                            double bottom_radius) {
  HWY_DYNAMIC_DISPATCH(AltitudesFromPerigee)(s, n, from_perigee, p2, bottom_radius);
}

}  // namespace skybake
#endif  // HWY_ONCE

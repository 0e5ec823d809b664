// ring_sun_sums over lanes (Highway, every target from one source): per lane
// the operations of transmittance_at_radius and lookup_sun_transmittance
// (table_lanes-inl.h) on the same operands, summed over the azimuths in
// order: the same bits as one sample at a time
// (tests/verify/ring_sun_sums_test.cpp).
#include "verify/kernels/ring_sun_sums.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "verify/kernels/ring_sun_sums.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/table_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {

void RingSunSums(const Texture& lut, const Atmosphere& atm, const double* radii,
                 const double* distances, const double* inverse_radii, size_t n, double height,
                 const double* cosines, size_t n_cosines, glm::dvec3* sums) {
  using D = hn::ScalableTag<double>;
  const D d;
  const size_t lanes = hn::Lanes(d);
  const Lanes<D> h = hn::Set(d, height);
  for (size_t k = 0; k < n; k += lanes) {
    const size_t count = std::min(lanes, n - k);
    const RadiusLanes<D> at = RadiusAt(d, lut, atm, LoadGroup(d, radii, k, count));
    const Lanes<D> dist = LoadGroup(d, distances, k, count);
    const Lanes<D> inverse = LoadGroup(d, inverse_radii, k, count);
    RgbLanes<D> sum{{hn::Zero(d), hn::Zero(d), hn::Zero(d)}};
    for (size_t j = 0; j < n_cosines; ++j) {
      // (height + distance c) / r, then clamp_cosine, as the one-value read.
      const Lanes<D> mu = ClampLanes(
          d, hn::Mul(hn::Add(h, hn::Mul(dist, hn::Set(d, cosines[j]))), inverse), -1.0, 1.0);
      const RgbLanes<D> t = SunTransmittance(d, lut, atm, at, mu);
      for (int c = 0; c < 3; ++c) sum.c[c] = hn::Add(sum.c[c], t.c[c]);
    }
    StoreRgb(d, sum, count, sums + k);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(RingSunSums);

void ring_sun_sums(const Texture& lut, const Atmosphere& atm, const double* radii,
                   const double* distances, const double* inverse_radii, size_t n, double height,
                   const double* cosines, size_t n_cosines, glm::dvec3* sums) {
  HWY_DYNAMIC_DISPATCH(RingSunSums)
  (lut, atm, radii, distances, inverse_radii, n, height, cosines, n_cosines, sums);
}

}  // namespace skybake
#endif  // HWY_ONCE

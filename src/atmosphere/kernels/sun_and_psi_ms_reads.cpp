// read_sun_and_psi_ms over lanes (Highway, every target from one source):
// per lane the texel coordinates of lookup_sun_transmittance and
// lookup_multiscattering (the same operations as the one-value functions)
// and their bilinear reads (table_lanes-inl.h): the same bits as one point
// at a time (tests/atmosphere/sun_and_psi_ms_reads_test.cpp). The
// terminator mapping's arctangents stay libm's, lane by lane.
#include "atmosphere/kernels/sun_and_psi_ms_reads.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/sun_and_psi_ms_reads.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/table_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace {

// lookup_multiscattering(lut, m, atm, r, mu_s)'s quad in each lane:
// multiscattering_uv_from_r_mu_s's operations; the terminator mapping's
// x_mu_s is unit_from_sun_cosine's own, lane by lane.
template <class D>
TexelQuad<D> MultiscatteringQuad(D d, const Atmosphere& atm, const Texture& lut,
                                 const MultiscatteringMapping& m, Lanes<D> r, Lanes<D> mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  r = ClampLanes(d, r, rb, rt);
  Lanes<D> x_mu;
  if (m.sun == SunMapping::linear) {
    x_mu = hn::Add(hn::Set(d, 0.5), hn::Mul(hn::Set(d, 0.5), ClampLanes(d, mu, -1.0, 1.0)));
  } else {
    HWY_ALIGN double rl[hn::MaxLanes(d)], ml[hn::MaxLanes(d)], xl[hn::MaxLanes(d)];
    hn::Store(r, d, rl);
    hn::Store(mu, d, ml);
    for (size_t k = 0; k < hn::Lanes(d); ++k) xl[k] = unit_from_sun_cosine(m, atm, rl[k], ml[k]);
    x_mu = hn::Load(d, xl);
  }
  Lanes<D> x_h = hn::Div(hn::Sub(r, hn::Set(d, rb)), hn::Set(d, rt - rb));
  if (m.altitude == AltitudeMapping::quadratic) x_h = hn::Sqrt(x_h);
  return TableQuad(d, lut, TexelCoord(d, x_mu, lut.width), TexelCoord(d, x_h, lut.height));
}

}  // namespace

void ReadSunAndPsiMs(const Atmosphere& atm, const Texture& transmittance_lut,
                     const Texture* multiscattering_lut, const MultiscatteringMapping& mapping,
                     const double* r, const double* mu_s, size_t n, glm::dvec3* sun,
                     glm::dvec3* ms) {
  using D = hn::ScalableTag<double>;
  const D d;
  const size_t lanes = hn::Lanes(d);
  for (size_t k = 0; k < n; k += lanes) {
    const size_t count = std::min(lanes, n - k);
    const Lanes<D> rv = LoadGroup(d, r, k, count), mv = LoadGroup(d, mu_s, k, count);
    const RadiusLanes<D> at = RadiusAt(d, transmittance_lut, atm, rv);
    StoreRgb(d,
             SunTransmittance(d, transmittance_lut, atm, at, ClampLanes(d, mv, -1.0, 1.0)),
             count, sun + k);
    if (multiscattering_lut) {
      const TexelQuad<D> q = MultiscatteringQuad(d, atm, *multiscattering_lut, mapping, rv, mv);
      StoreRgb(d, ReadRgb(d, multiscattering_lut->data.data(), q), count, ms + k);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(ReadSunAndPsiMs);

void read_sun_and_psi_ms(const Atmosphere& atm, const Texture& transmittance_lut,
                         const Texture* multiscattering_lut, const MultiscatteringMapping& mapping,
                         const double* r, const double* mu_s, size_t n, glm::dvec3* sun,
                         glm::dvec3* ms) {
  HWY_DYNAMIC_DISPATCH(ReadSunAndPsiMs)
  (atm, transmittance_lut, multiscattering_lut, mapping, r, mu_s, n, sun, ms);
}

}  // namespace skybake
#endif  // HWY_ONCE

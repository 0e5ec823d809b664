// skyview_row_luminance over lanes (Highway, every target from one source):
// per lane the operations of skyview_texel_luminance in the same order on
// the same operands, with the table reads of table_lanes-inl.h, so the same
// bits as one texel at a time (tests/atmosphere/simd_targets_test.cpp).
#include "atmosphere/kernels/skyview_row_luminance.hpp"

#include <algorithm>
#include <vector>

#include "atmosphere/phase.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/skyview_row_luminance.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/table_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace {

// The texels of one group, `count` of them (a short group repeats its last
// texel's cos_phi in the spare lanes); phase[(c * 3 + channel) * N + lane]
// is sigma_s p(nu) of component c.
template <class D>
void GroupLuminance(D d, const SkyviewRowMarch& row, const Atmosphere& atm,
                    const Texture& transmittance_lut, const Texture& multiscattering_lut,
                    Lanes<D> cos_phi, const double* phase, double cos_theta_s, double sin_theta_s,
                    size_t count, glm::dvec3* out) {
  const size_t nc = row.components.size(), n = hn::Lanes(d);
  const Lanes<D> across_scale = hn::Mul(cos_phi, hn::Set(d, sin_theta_s));
  RgbLanes<D> lum{{hn::Zero(d), hn::Zero(d), hn::Zero(d)}};
  const double* density = row.densities.data();
  for (const SkyviewRowSegment& seg : row.segments) {
    Lanes<D> ssp[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for (size_t c = 0; c < nc; ++c)
      for (int ch = 0; ch < 3; ++ch)
        ssp[ch] = hn::Add(ssp[ch], hn::Mul(hn::Set(d, density[c]),
                                           hn::LoadU(d, phase + (c * 3 + ch) * n)));
    density += nc;
    const Lanes<D> mu_s = ClampLanes(d,
                                     hn::Add(hn::Set(d, seg.along * cos_theta_s),
                                             hn::Mul(hn::Set(d, seg.across), across_scale)),
                                     -1.0, 1.0);
    const RgbLanes<D> t_sun = SunTransmittance(
        d, transmittance_lut, atm, RadiusAt(d, transmittance_lut, seg.transmittance), mu_s);
    const MultiscatteringAtRadius& ms_at = seg.multiscattering;
    const Lanes<D> x = hn::Add(hn::Set(d, 0.5), hn::Mul(hn::Set(d, 0.5), mu_s));
    const Lanes<D> u = hn::Add(hn::Set(d, ms_at.u_offset), hn::Mul(x, hn::Set(d, ms_at.u_scale)));
    const RgbLanes<D> ms =
        ReadRgb(d, multiscattering_lut.data.data(), RowQuad(d, multiscattering_lut, ms_at.row, u));
    for (int ch = 0; ch < 3; ++ch) {  // eq. 11
      const Lanes<D> source = hn::Add(hn::Mul(t_sun.c[ch], ssp[ch]),
                                      hn::Mul(ms.c[ch], hn::Set(d, seg.sigma_s[ch])));
      lum.c[ch] = hn::Add(lum.c[ch], hn::Mul(hn::Set(d, seg.view_weight[ch]), source));
    }
  }
  StoreRgb(d, lum, count, out);
}

}  // namespace

// Every texel of the row, the linear sun mapping only.
void SkyviewRowLuminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                         const Texture& transmittance_lut, const Texture& multiscattering_lut,
                         const double* cos_phi, const double* nu, int n, double cos_theta_s,
                         double sin_theta_s, glm::dvec3* out) {
  const hn::ScalableTag<double> d;
  const size_t lanes = hn::Lanes(d), nc = row.components.size();
  std::vector<double> phase(nc * 3 * lanes);
  for (size_t k = 0; k < size_t(n); k += lanes) {
    const size_t count = std::min(lanes, size_t(n) - k);
    for (size_t c = 0; c < nc; ++c) {
      const MediumComponent& m = *row.components[c];
      for (size_t lane = 0; lane < lanes; ++lane) {
        const double nu_lane = nu[k + std::min(lane, count - 1)];
        const glm::dvec3 sp = m.scattering_per_m * phase_function(m.phase, m.g, nu_lane);
        for (int ch = 0; ch < 3; ++ch) phase[(c * 3 + ch) * lanes + lane] = sp[ch];
      }
    }
    GroupLuminance(d, row, atm, transmittance_lut, multiscattering_lut,
                   LoadGroup(d, cos_phi, k, count), phase.data(), cos_theta_s, sin_theta_s, count,
                   out + k);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(SkyviewRowLuminance);

void skyview_row_luminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                           const Texture& transmittance_lut, const Texture& multiscattering_lut,
                           const double* cos_phi, const double* nu, int n, double cos_theta_s,
                           double sin_theta_s, glm::dvec3* out) {
  if (!row.segments.empty() &&
      row.segments.front().multiscattering.mapping.sun == SunMapping::linear) {
    HWY_DYNAMIC_DISPATCH(SkyviewRowLuminance)
    (row, atm, transmittance_lut, multiscattering_lut, cos_phi, nu, n, cos_theta_s, sin_theta_s,
     out);
    return;
  }
  // The terminator mapping reads Psi_ms through an arctangent per lookup.
  std::vector<glm::dvec3> scratch;
  for (int k = 0; k < n; ++k)
    out[k] = skyview_texel_luminance(row, atm, transmittance_lut, multiscattering_lut, cos_phi[k],
                                     cos_theta_s, sin_theta_s, nu[k], scratch);
}

}  // namespace skybake
#endif  // HWY_ONCE

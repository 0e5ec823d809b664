// sunlit_sums over lanes (Highway, every target from one source): per lane
// the operations of multiscattering_lut.cpp's sunlit_direction and its sum,
// in the same order on the same operands, with the reads of
// table_lanes-inl.h: the same bits as one sun at a time
// (tests/atmosphere/simd_targets_test.cpp).
#include "atmosphere/kernels/sunlit_sums.hpp"

#include <algorithm>

#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "core/math.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/sunlit_sums.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "atmosphere/kernels/table_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace {

// The lit ground where the march ends on it, lane by lane (about one read per
// direction, against one per segment above): sunlit_direction's last term.
template <class D>
void AddLitGround(D d, const Atmosphere& atm, const Texture& transmittance_lut,
                  const DirectionMarch& m, Lanes<D> sx, Lanes<D> mu_s, RgbLanes<D>& l_prime) {
  HWY_ALIGN double x[hn::MaxLanes(d)], z[hn::MaxLanes(d)], l[3][hn::MaxLanes(d)];
  hn::Store(sx, d, x);
  hn::Store(mu_s, d, z);
  for (int ch = 0; ch < 3; ++ch) hn::Store(l_prime.c[ch], d, l[ch]);
  for (size_t lane = 0; lane < hn::Lanes(d); ++lane) {
    const double mu_g = clamp_cosine(glm::dot(m.ground_up, glm::dvec3(x[lane], 0.0, z[lane])));
    if (!(mu_g > 0.0)) continue;
    const glm::dvec3 t_sun =
        lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius_m, mu_g);
    const glm::dvec3 lit = m.ground_transmittance * t_sun * mu_g * atm.ground_albedo / kPi;
    for (int ch = 0; ch < 3; ++ch) l[ch][lane] += lit[ch];
  }
  for (int ch = 0; ch < 3; ++ch) l_prime.c[ch] = hn::Load(d, l[ch]);
}

// sunlit_direction for the suns (sx, 0, mu_s) of the lanes.
template <class D>
RgbLanes<D> SunlitDirection(D d, const Atmosphere& atm, const Texture& transmittance_lut,
                            const DirectionMarch& m, Lanes<D> sx, Lanes<D> mu_s) {
  const Lanes<D> iso = hn::Set(d, isotropic_phase());
  RgbLanes<D> l_prime{{hn::Zero(d), hn::Zero(d), hn::Zero(d)}};
  for (size_t i = 0; i < m.points.size(); ++i) {
    const glm::dvec3& p = m.points[i];
    // glm::dot(p, sun) / r: (x sx + y 0) + z mu_s.
    const Lanes<D> dot = hn::Add(hn::Add(hn::Mul(hn::Set(d, p.x), sx), hn::Set(d, p.y * 0.0)),
                                 hn::Mul(hn::Set(d, p.z), mu_s));
    const Lanes<D> mu = ClampLanes(d, hn::Div(dot, hn::Set(d, m.radii[i])), -1.0, 1.0);
    const RgbLanes<D> t_sun =
        SunTransmittance(d, transmittance_lut, atm, RadiusAt(d, transmittance_lut, m.sun_reads[i]), mu);
    for (int ch = 0; ch < 3; ++ch)
      l_prime.c[ch] = hn::Add(
          l_prime.c[ch], hn::Mul(hn::Mul(hn::Set(d, m.scattered[i][ch]), t_sun.c[ch]), iso));
  }
  if (m.ground) AddLitGround(d, atm, transmittance_lut, m, sx, mu_s, l_prime);
  return l_prime;
}

}  // namespace

void SunlitSums(const Atmosphere& atm, const Texture& transmittance_lut,
                const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                const double* mu_s, int n, glm::dvec3* l2) {
  using D = hn::ScalableTag<double>;
  const D d;
  const size_t lanes = hn::Lanes(d);
  const bool weighted = !rule.weights.empty();
  for (size_t j = 0; j < size_t(n); j += lanes) {
    const size_t count = std::min(lanes, size_t(n) - j);
    const Lanes<D> mu = LoadGroup(d, mu_s, j, count);
    // The sun (safe_sqrt(1 - mu_s^2), 0, mu_s).
    const Lanes<D> sx =
        hn::Sqrt(hn::Max(hn::Zero(d), hn::Sub(hn::Set(d, 1.0), hn::Mul(mu, mu))));
    RgbLanes<D> sum{{hn::Zero(d), hn::Zero(d), hn::Zero(d)}};
    for (size_t k = 0; k < marches.size(); ++k) {
      const Lanes<D> w = hn::Set(d, weighted ? rule.weights[k] : 1.0);
      const RgbLanes<D> l_prime = SunlitDirection(d, atm, transmittance_lut, marches[k], sx, mu);
      for (int ch = 0; ch < 3; ++ch) sum.c[ch] = hn::Add(sum.c[ch], hn::Mul(w, l_prime.c[ch]));
    }
    StoreRgb(d, sum, count, l2 + j);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(SunlitSums);

void sunlit_sums(const Atmosphere& atm, const Texture& transmittance_lut,
                 const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                 const double* mu_s, int n, glm::dvec3* l2) {
  HWY_DYNAMIC_DISPATCH(SunlitSums)(atm, transmittance_lut, marches, rule, mu_s, n, l2);
}

}  // namespace skybake
#endif  // HWY_ONCE

// sunlit_sums_wide: the multiple-scattering table's sums over directions for
// four suns at a time where AVX2 runs (core/simd_switches.hpp). Per lane the
// operations of multiscattering_lut.cpp's sunlit_direction and its sum, in
// the same order on the same operands, with the reads of
// atmosphere/kernels/table_read_lanes.hpp: the same bits (tests/atmosphere/
// avx2_bakes_test.cpp bakes with and without it and compares).
#include "atmosphere/kernels/sunlit_sums.hpp"

#include <cmath>

#include "atmosphere/kernels/table_read_lanes.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
// The lit ground where the march ends on it, lane by lane (about one read per
// direction, against one per segment above): sunlit_direction's last term.
SKYBAKE_AVX2 void add_lit_ground(const Atmosphere& atm, const Texture& transmittance_lut,
                                 const DirectionMarch& m, __m256d sx, __m256d mu_s,
                                 __m256d l_prime[3]) {
  alignas(32) double x[4], z[4], l[3][4];
  _mm256_store_pd(x, sx);
  _mm256_store_pd(z, mu_s);
  for (int ch = 0; ch < 3; ++ch) _mm256_store_pd(l[ch], l_prime[ch]);
  for (int lane = 0; lane < 4; ++lane) {
    const double mu_g = clamp_cosine(glm::dot(m.ground_up, glm::dvec3(x[lane], 0.0, z[lane])));
    if (!(mu_g > 0.0)) continue;
    const glm::dvec3 t_sun =
        lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius_m, mu_g);
    const glm::dvec3 lit = m.ground_transmittance * t_sun * mu_g * atm.ground_albedo / kPi;
    for (int ch = 0; ch < 3; ++ch) l[ch][lane] += lit[ch];
  }
  for (int ch = 0; ch < 3; ++ch) l_prime[ch] = _mm256_load_pd(l[ch]);
}

// sunlit_direction for the suns (sx, 0, mu_s) of the four lanes.
SKYBAKE_AVX2 void sunlit_direction_lanes(const Atmosphere& atm, const Texture& transmittance_lut,
                                         const DirectionMarch& m, __m256d sx, __m256d mu_s,
                                         __m256d l_prime[3]) {
  const __m256d zero = _mm256_setzero_pd(), iso = _mm256_set1_pd(isotropic_phase());
  for (int ch = 0; ch < 3; ++ch) l_prime[ch] = zero;
  for (size_t i = 0; i < m.points.size(); ++i) {
    const glm::dvec3& p = m.points[i];
    // glm::dot(p, sun) / r: (x sx + y 0) + z mu_s.
    const __m256d dot = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(p.x), sx), _mm256_set1_pd(p.y * 0.0)),
        _mm256_mul_pd(_mm256_set1_pd(p.z), mu_s));
    const __m256d mu = clamp_lanes(_mm256_div_pd(dot, _mm256_set1_pd(m.radii[i])), -1.0, 1.0);
    const RgbLanes t_sun = sun_transmittance_lanes(m.sun_reads[i], transmittance_lut.width,
                                                   atm.bottom_radius_m, mu);
    for (int ch = 0; ch < 3; ++ch)
      l_prime[ch] = _mm256_add_pd(
          l_prime[ch],
          _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(m.scattered[i][ch]), t_sun.c[ch]), iso));
  }
  if (m.ground) add_lit_ground(atm, transmittance_lut, m, sx, mu_s, l_prime);
}

SKYBAKE_AVX2 int sunlit_sums_avx2(const Atmosphere& atm, const Texture& transmittance_lut,
                                  const std::vector<DirectionMarch>& marches,
                                  const SphereRule& rule, const double* mu_s, int n,
                                  glm::dvec3* l2) {
  const bool weighted = !rule.weights.empty();
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    const __m256d mu = _mm256_loadu_pd(mu_s + j);
    // The sun (safe_sqrt(1 - mu_s^2), 0, mu_s).
    const __m256d sx =
        _mm256_sqrt_pd(_mm256_max_pd(zero, _mm256_sub_pd(one, _mm256_mul_pd(mu, mu))));
    __m256d sum[3] = {zero, zero, zero};
    for (size_t k = 0; k < marches.size(); ++k) {
      const __m256d w = _mm256_set1_pd(weighted ? rule.weights[k] : 1.0);
      __m256d l_prime[3];
      sunlit_direction_lanes(atm, transmittance_lut, marches[k], sx, mu, l_prime);
      for (int ch = 0; ch < 3; ++ch) sum[ch] = _mm256_add_pd(sum[ch], _mm256_mul_pd(w, l_prime[ch]));
    }
    alignas(32) double lanes[3][4];
    for (int ch = 0; ch < 3; ++ch) _mm256_store_pd(lanes[ch], sum[ch]);
    for (int lane = 0; lane < 4; ++lane)
      l2[j + lane] = glm::dvec3(lanes[0][lane], lanes[1][lane], lanes[2][lane]);
  }
  return j;
}
#endif

}  // namespace

int sunlit_sums_wide(const Atmosphere& atm, const Texture& transmittance_lut,
                     const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                     const double* mu_s, int n, glm::dvec3* l2) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) return sunlit_sums_avx2(atm, transmittance_lut, marches, rule, mu_s, n, l2);
#endif
  (void)atm, (void)transmittance_lut, (void)marches, (void)rule, (void)mu_s, (void)n, (void)l2;
  return 0;
}

}  // namespace skybake

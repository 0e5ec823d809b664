#include "atmosphere/ring_sun_wide.hpp"

#include "atmosphere/wide_lookups.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
SKYBAKE_AVX2 void ring_sun_sums_avx2(const Texture& lut, double bottom_m,
                                     const TransmittanceAtRadius* reads, const double* distances,
                                     const double* inverse_radii, size_t n, double height,
                                     const double cosines[4], glm::dvec3* sums) {
  const __m256d c = _mm256_loadu_pd(cosines);
  const __m256d h = _mm256_set1_pd(height);
  alignas(32) double lanes[3][4];
  for (size_t i = 0; i < n; ++i) {
    // (height + distance c) / r, then clamp_cosine, as the one-value read.
    const __m256d mu =
        clamp_lanes(_mm256_mul_pd(_mm256_add_pd(h, _mm256_mul_pd(_mm256_set1_pd(distances[i]), c)),
                                  _mm256_set1_pd(inverse_radii[i])),
                    -1.0, 1.0);
    const RgbLanes t = sun_transmittance_lanes(reads[i], lut.width, bottom_m, mu);
    for (int ch = 0; ch < 3; ++ch) _mm256_store_pd(lanes[ch], t.c[ch]);
    glm::dvec3 sum(0.0);
    for (int lane = 0; lane < 4; ++lane)
      sum += glm::dvec3(lanes[0][lane], lanes[1][lane], lanes[2][lane]);
    sums[i] = sum;
  }
}
#endif

}  // namespace

bool ring_sun_sums_wide(const Texture& lut, double bottom_m, const TransmittanceAtRadius* reads,
                        const double* distances, const double* inverse_radii, size_t n,
                        double height, const double cosines[4], glm::dvec3* sums) {
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) {
    ring_sun_sums_avx2(lut, bottom_m, reads, distances, inverse_radii, n, height, cosines, sums);
    return true;
  }
#endif
  (void)lut, (void)bottom_m, (void)reads, (void)distances, (void)inverse_radii, (void)n,
      (void)height, (void)cosines, (void)sums;
  return false;
}

}  // namespace skybake

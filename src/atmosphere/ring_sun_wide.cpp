#include "atmosphere/ring_sun_wide.hpp"

#include "atmosphere/wide_lookups.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
// The four azimuths' texel coordinates in the lanes of one group, then each
// azimuth's read with its channels in one vector (bilinear_rgb_texels), so
// that the sum over azimuths is three lanes added at once, in the one-value
// loop's order (0 + a0 + a1 + a2 + a3), with no gathers and no horizontal sum.
SKYBAKE_AVX2 void ring_sun_sums_avx2(const Texture& lut, double bottom_m,
                                     const TransmittanceAtRadius* reads, const double* distances,
                                     const double* inverse_radii, size_t n, double height,
                                     const double cosines[4], glm::dvec3* sums) {
  const __m256d c = _mm256_loadu_pd(cosines);
  const __m256d h = _mm256_set1_pd(height);
  alignas(32) double f[4], lit[4];
  alignas(16) int o0[4], o1[4];
  alignas(32) double sum[4];
  for (size_t i = 0; i < n; ++i) {
    // (height + distance c) / r, then clamp_cosine, as the one-value read.
    const __m256d mu =
        clamp_lanes(_mm256_mul_pd(_mm256_add_pd(h, _mm256_mul_pd(_mm256_set1_pd(distances[i]), c)),
                                  _mm256_set1_pd(inverse_radii[i])),
                    -1.0, 1.0);
    const TransmittanceAtRadius& at = reads[i];
    const SunCoordLanes s = sun_coord_lanes(at, bottom_m, mu);
    const AxisLanes a = bilinear_axis_lanes(lut.width, at.row.channels, s.u);
    _mm256_store_pd(f, a.f);
    _mm256_store_pd(lit, _mm256_castsi256_pd(_mm256_xor_si256(
                             _mm256_castpd_si256(s.ground), _mm256_set1_epi64x(-1))));
    _mm_store_si128(reinterpret_cast<__m128i*>(o0), a.o0);
    _mm_store_si128(reinterpret_cast<__m128i*>(o1), a.o1);
    __m256d total = _mm256_setzero_pd();
    for (int lane = 0; lane < 4; ++lane) {
      const __m256d t =
          bilinear_rgb_texels(at.row.row0, at.row.row1, o0[lane], o1[lane], f[lane], at.row.fy);
      // Vis = 0 below the horizon: the one-value loop adds a zero read.
      total = _mm256_add_pd(total, _mm256_and_pd(t, _mm256_set1_pd(lit[lane])));
    }
    _mm256_store_pd(sum, total);
    sums[i] = glm::dvec3(sum[0], sum[1], sum[2]);
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

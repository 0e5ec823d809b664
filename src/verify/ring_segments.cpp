#include "verify/ring_segments.hpp"

#include <algorithm>

#include "atmosphere/geometry.hpp"
#include "core/wide_intrinsics.hpp"

namespace skybake {
namespace {

void segment_terms(const double* ends, size_t i, const glm::dvec3& extinction, const double* em,
               double r, double mu, double bottom_m, RingSegmentTerms& out) {
  const double dt = ends[i + 1] - ends[i];
  for (int c = 0; c < 3; ++c)  // segment_weights_from_expm1
    out.weight[c][i] = extinction[c] > 0.0 ? -em[c] / extinction[c] : dt;
  const double lit_at = ends[i] + weight_centroid(extinction, dt, em[3]);
  const double lit_radius = std::max(radius_after(r, mu, lit_at), bottom_m);
  out.lit_at[i] = lit_at;
  out.lit_radius[i] = lit_radius;
  out.inverse_radius[i] = 1.0 / lit_radius;
}

#if SKYBAKE_HAS_AVX2
// segment_terms for segments i..i+3.
SKYBAKE_AVX2 void segment_terms_avx2(const double* ends, size_t i, const glm::dvec3* extinction,
                             const double* expm1s, double r, double mu, double bottom_m,
                             RingSegmentTerms& out) {
  const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
  const __m256d start = _mm256_loadu_pd(ends + i);
  const __m256d dt = _mm256_sub_pd(_mm256_loadu_pd(ends + i + 1), start);
  // The four segments' expm1s, four apiece: transposed to one vector per term.
  const __m256d a = _mm256_loadu_pd(expm1s + 4 * i), b = _mm256_loadu_pd(expm1s + 4 * i + 4);
  const __m256d c = _mm256_loadu_pd(expm1s + 4 * i + 8), d = _mm256_loadu_pd(expm1s + 4 * i + 12);
  const __m256d ab_lo = _mm256_unpacklo_pd(a, b), ab_hi = _mm256_unpackhi_pd(a, b);
  const __m256d cd_lo = _mm256_unpacklo_pd(c, d), cd_hi = _mm256_unpackhi_pd(c, d);
  const __m256d em[4] = {_mm256_permute2f128_pd(ab_lo, cd_lo, 0x20),
                         _mm256_permute2f128_pd(ab_hi, cd_hi, 0x20),
                         _mm256_permute2f128_pd(ab_lo, cd_lo, 0x31),
                         _mm256_permute2f128_pd(ab_hi, cd_hi, 0x31)};
  const glm::dvec3* e = extinction + i;
  __m256d ext[3];
  for (int ch = 0; ch < 3; ++ch) {
    ext[ch] = _mm256_setr_pd(e[0][ch], e[1][ch], e[2][ch], e[3][ch]);
    const __m256d w = _mm256_div_pd(_mm256_xor_pd(em[ch], sign), ext[ch]);
    _mm256_storeu_pd(&out.weight[ch][i],
                     _mm256_blendv_pd(dt, w, _mm256_cmp_pd(ext[ch], zero, _CMP_GT_OQ)));
  }
  // weight_centroid
  const __m256d x = _mm256_mul_pd(
      _mm256_div_pd(_mm256_add_pd(_mm256_add_pd(ext[0], ext[1]), ext[2]), _mm256_set1_pd(3.0)), dt);
  const __m256d thin = _mm256_sub_pd(_mm256_set1_pd(0.5), _mm256_div_pd(x, _mm256_set1_pd(12.0)));
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d thick = _mm256_sub_pd(_mm256_div_pd(one, x), _mm256_div_pd(one, em[3]));
  const __m256d fraction =
      _mm256_blendv_pd(thick, thin, _mm256_cmp_pd(x, _mm256_set1_pd(1e-4), _CMP_LT_OQ));
  const __m256d lit_at = _mm256_add_pd(start, _mm256_mul_pd(fraction, dt));
  // radius_after: safe_sqrt(d d + 2 r mu d + r r), at least Rb (the operand
  // order of std::max's, NaN and signed zeros included).
  const __m256d q = _mm256_add_pd(
      _mm256_add_pd(_mm256_mul_pd(lit_at, lit_at),
                    _mm256_mul_pd(_mm256_set1_pd(2.0 * r * mu), lit_at)),
      _mm256_set1_pd(r * r));
  const __m256d radius =
      _mm256_max_pd(_mm256_set1_pd(bottom_m), _mm256_sqrt_pd(_mm256_max_pd(zero, q)));
  _mm256_storeu_pd(&out.lit_at[i], lit_at);
  _mm256_storeu_pd(&out.lit_radius[i], radius);
  _mm256_storeu_pd(&out.inverse_radius[i], _mm256_div_pd(one, radius));
}
#endif

}  // namespace

void ring_segment_terms(const double* ends, size_t n, const glm::dvec3* extinction,
                        const double* expm1s, double r, double mu, double bottom_m,
                        RingSegmentTerms& out) {
  for (std::vector<double>* v : {&out.weight[0], &out.weight[1], &out.weight[2], &out.lit_at,
                                 &out.lit_radius, &out.inverse_radius})
    v->resize(n);
  size_t i = 0;
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled())
    for (; i + 4 <= n; i += 4) segment_terms_avx2(ends, i, extinction, expm1s, r, mu, bottom_m, out);
#endif
  for (; i < n; ++i) segment_terms(ends, i, extinction[i], expm1s + 4 * i, r, mu, bottom_m, out);
}

}  // namespace skybake

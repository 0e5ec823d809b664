// The row blend in SSE2, its AVX2 twin and plain C++ for CPUs without SSE2.
// See the header.
#include "atmosphere/kernels/row_blend.hpp"

#include "core/wide_intrinsics.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
// blend_rows two texels at a time; returns how many texels it did.
SKYBAKE_AVX2 int blend_rows_avx2(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  const __m256 w0 = _mm256_set1_ps(w[0]), w1 = _mm256_set1_ps(w[1]), w2 = _mm256_set1_ps(w[2]),
               w3 = _mm256_set1_ps(w[3]);
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m256 a = _mm256_mul_ps(w0, _mm256_loadu_ps(rows[0][i].v));
    const __m256 b = _mm256_mul_ps(w1, _mm256_loadu_ps(rows[1][i].v));
    const __m256 c = _mm256_mul_ps(w2, _mm256_loadu_ps(rows[2][i].v));
    const __m256 d = _mm256_mul_ps(w3, _mm256_loadu_ps(rows[3][i].v));
    _mm256_storeu_ps(out[i].v, _mm256_add_ps(_mm256_add_ps(a, b), _mm256_add_ps(c, d)));
  }
  return i;
}

#endif

}  // namespace

void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) first = blend_rows_avx2(rows, w, n, out);
#endif
#if defined(__SSE2__)
  const __m128 w0 = _mm_set1_ps(w[0]), w1 = _mm_set1_ps(w[1]), w2 = _mm_set1_ps(w[2]),
               w3 = _mm_set1_ps(w[3]);
  for (int i = first; i < n; ++i) {
    const __m128 s = _mm_add_ps(_mm_add_ps(_mm_mul_ps(w0, _mm_load_ps(rows[0][i].v)),
                                           _mm_mul_ps(w1, _mm_load_ps(rows[1][i].v))),
                                _mm_add_ps(_mm_mul_ps(w2, _mm_load_ps(rows[2][i].v)),
                                           _mm_mul_ps(w3, _mm_load_ps(rows[3][i].v))));
    _mm_store_ps(out[i].v, s);
  }
#else
  for (int i = first; i < n; ++i)
    for (int c = 0; c < 4; ++c)
      out[i].v[c] = (w[0] * rows[0][i].v[c] + w[1] * rows[1][i].v[c]) +
                    (w[2] * rows[2][i].v[c] + w[3] * rows[3][i].v[c]);
#endif
}

}  // namespace skybake

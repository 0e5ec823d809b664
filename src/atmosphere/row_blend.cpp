// The row loops of the multiple-scattering pass in SSE2, their AVX2 twins
// and plain C++ for CPUs without SSE2. See the header.
#include "atmosphere/row_blend.hpp"

#include <algorithm>

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

// mu_s_at_node four cosines at a time: _mm256_max_pd(lo, v) is
// std::max(v, lo) and _mm256_min_pd(hi, v) std::min(v, hi), signed zeros
// included (batch_taps.cpp). Returns how many it did.
SKYBAKE_AVX2 int mu_s_at_node_avx2(double r, double s, double inv_r_i, const double* mu_s,
                                   const double* nu, int n, double* out) {
  const __m256d r4 = _mm256_set1_pd(r), s4 = _mm256_set1_pd(s), inv_r_i4 = _mm256_set1_pd(inv_r_i);
  const __m256d lo = _mm256_set1_pd(-1.0), hi = _mm256_set1_pd(1.0);
  int x = 0;
  for (; x + 4 <= n; x += 4) {
    const __m256d c = _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(r4, _mm256_loadu_pd(mu_s + x)),
                                                  _mm256_mul_pd(s4, _mm256_loadu_pd(nu + x))),
                                    inv_r_i4);
    _mm256_storeu_pd(out + x, _mm256_min_pd(hi, _mm256_max_pd(lo, c)));
  }
  return x;
}

// add_bilinear_row two texels at a time: a 256-bit load takes a texel's
// s00 and s01 (or s10 and s11) together, and two such loads are regrouped
// into (s00 of x, s00 of x + 1) and (s01 of x, s01 of x + 1).
SKYBAKE_AVX2 int add_bilinear_row_avx2(const Rgb4* slice, const BilinearTaps& t, const Rgb4& wS,
                                       int n, Rgb4* sum) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 ws = _mm256_set_m128(_mm_load_ps(wS.v), _mm_load_ps(wS.v));
  int x = 0;
  for (; x + 2 <= n; x += 2) {
    const __m256 a0 = _mm256_loadu_ps(slice[t.nu_i0[x] + t.tap_i0[x]].v);
    const __m256 a1 = _mm256_loadu_ps(slice[t.nu_i0[x + 1] + t.tap_i0[x + 1]].v);
    const __m256 b0 = _mm256_loadu_ps(slice[t.nu_i1[x] + t.tap_i0[x]].v);
    const __m256 b1 = _mm256_loadu_ps(slice[t.nu_i1[x + 1] + t.tap_i0[x + 1]].v);
    const __m256 s00 = _mm256_permute2f128_ps(a0, a1, 0x20), s01 = _mm256_permute2f128_ps(a0, a1, 0x31);
    const __m256 s10 = _mm256_permute2f128_ps(b0, b1, 0x20), s11 = _mm256_permute2f128_ps(b0, b1, 0x31);
    const __m256 l1 = _mm256_set_m128(_mm_set1_ps(float(t.tap_w[x + 1])), _mm_set1_ps(float(t.tap_w[x])));
    const __m256 n1 = _mm256_set_m128(_mm_set1_ps(t.nu_w[x + 1]), _mm_set1_ps(t.nu_w[x]));
    const __m256 l0 = _mm256_sub_ps(one, l1), n0 = _mm256_sub_ps(one, n1);
    const __m256 a = _mm256_add_ps(_mm256_mul_ps(l0, s00), _mm256_mul_ps(l1, s01));
    const __m256 b = _mm256_add_ps(_mm256_mul_ps(l0, s10), _mm256_mul_ps(l1, s11));
    const __m256 L = _mm256_add_ps(_mm256_mul_ps(n0, a), _mm256_mul_ps(n1, b));
    _mm256_storeu_ps(sum[x].v, _mm256_add_ps(_mm256_loadu_ps(sum[x].v), _mm256_mul_ps(ws, L)));
  }
  return x;
}
#endif

// sum += wS lerp(lerp(s00, s01, lw), lerp(s10, s11, lw), nw), s01 = s00 + 1
// texel along mu_s.
inline void add_bilinear(const Rgb4* s0, const Rgb4* s1, float lw, float nw, const Rgb4& wS,
                         Rgb4& sum) {
#if defined(__SSE2__)
  const __m128 l1 = _mm_set1_ps(lw), l0 = _mm_set1_ps(1.0f - lw);
  const __m128 n1 = _mm_set1_ps(nw), n0 = _mm_set1_ps(1.0f - nw);
  const __m128 a = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s0[0].v)), _mm_mul_ps(l1, _mm_load_ps(s0[1].v)));
  const __m128 b = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s1[0].v)), _mm_mul_ps(l1, _mm_load_ps(s1[1].v)));
  const __m128 L = _mm_add_ps(_mm_mul_ps(n0, a), _mm_mul_ps(n1, b));
  _mm_store_ps(sum.v, _mm_add_ps(_mm_load_ps(sum.v), _mm_mul_ps(_mm_load_ps(wS.v), L)));
#else
  for (int c = 0; c < 4; ++c) {
    const float a = (1.0f - lw) * s0[0].v[c] + lw * s0[1].v[c];
    const float b = (1.0f - lw) * s1[0].v[c] + lw * s1[1].v[c];
    sum.v[c] += wS.v[c] * ((1.0f - nw) * a + nw * b);
  }
#endif
}

}  // namespace

void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) first = blend_rows_avx2(rows, w, n, out);
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

void mu_s_at_node(double r, double s, double inv_r_i, const double* mu_s, const double* nu, int n,
                  double* out) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) first = mu_s_at_node_avx2(r, s, inv_r_i, mu_s, nu, n, out);
#endif
  for (int x = first; x < n; ++x)
    out[x] = std::min(std::max((r * mu_s[x] + s * nu[x]) * inv_r_i, -1.0), 1.0);
}

void add_bilinear_row(const Rgb4* slice, const BilinearTaps& t, const Rgb4& wS, int n,
                      Rgb4* sum) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) first = add_bilinear_row_avx2(slice, t, wS, n, sum);
#endif
  for (int x = first; x < n; ++x)
    add_bilinear(&slice[t.nu_i0[x] + t.tap_i0[x]], &slice[t.nu_i1[x] + t.tap_i0[x]],
                 float(t.tap_w[x]), t.nu_w[x], wS, sum[x]);
}

}  // namespace skybake

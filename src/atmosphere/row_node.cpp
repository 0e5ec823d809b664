// The AVX2 loop of one node of a multiple-scattering row. See the header.
#include "atmosphere/row_node.hpp"

#include <algorithm>

#include "core/wide_intrinsics.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
// The loop's constants, in registers.
struct NodeLanes {
  __m256d r, s, inv_r_i, one, zero, minus_rb, rb2, H2, d_min, inv_span, inv_A, last, below_last;
  double mu_s_min;
};

// mu_s_at_node_avx2 (row_blend.cpp) and mu_s_taps_avx2 (batch_taps.cpp) for
// the four texels from x, operation for operation: each texel's first read
// (the tap plus its nu_i0), second (plus nu_i1) and float(w), which is
// _mm256_cvtpd_ps's rounding.
SKYBAKE_AVX2 inline void node_taps(const NodeLanes& k, const NodeRow& q, int x, int* at0,
                                   int* at1, float* lw) {
  const __m256d c = _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(k.r, _mm256_loadu_pd(q.mu_s + x)),
                                                _mm256_mul_pd(k.s, _mm256_loadu_pd(q.nu + x))),
                                  k.inv_r_i);
  const __m256d m = clamp_lanes(clamp_lanes(c, -1.0, 1.0), k.mu_s_min, 1.0);
  const __m256d root = _mm256_sqrt_pd(
      _mm256_max_pd(k.zero, _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(k.rb2, m), m), k.H2)));
  const __m256d d = _mm256_add_pd(_mm256_mul_pd(k.minus_rb, m), root);
  const __m256d a = _mm256_mul_pd(_mm256_sub_pd(d, k.d_min), k.inv_span);
  const __m256d u = _mm256_div_pd(
      _mm256_max_pd(k.zero, _mm256_sub_pd(k.one, _mm256_mul_pd(a, k.inv_A))), _mm256_add_pd(k.one, a));
  const __m256d t = _mm256_mul_pd(clamp_lanes(u, 0.0, 1.0), k.last);
  const __m256d i = _mm256_min_pd(k.below_last, _mm256_cvtepi32_pd(_mm256_cvttpd_epi32(t)));
  _mm_storeu_ps(lw + x, _mm256_cvtpd_ps(_mm256_sub_pd(t, i)));
  const __m128i tap = _mm256_cvttpd_epi32(i);
  auto plus = [&](const int* offset) {
    return _mm_add_epi32(tap, _mm_loadu_si128(reinterpret_cast<const __m128i*>(offset + x)));
  };
  _mm_storeu_si128(reinterpret_cast<__m128i*>(at0 + x), plus(q.nu_i0));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(at1 + x), plus(q.nu_i1));
}

// add_bilinear_row_avx2 (row_blend.cpp) for texels x and x + 1.
SKYBAKE_AVX2 inline void node_reads(const Rgb4* slice, const int* at0, const int* at1,
                                    const float* lw, const float* nu_w, __m256 ws, int x,
                                    Rgb4* sum) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 a0 = _mm256_loadu_ps(slice[at0[x]].v), a1 = _mm256_loadu_ps(slice[at0[x + 1]].v);
  const __m256 b0 = _mm256_loadu_ps(slice[at1[x]].v), b1 = _mm256_loadu_ps(slice[at1[x + 1]].v);
  const __m256 s00 = _mm256_permute2f128_ps(a0, a1, 0x20), s01 = _mm256_permute2f128_ps(a0, a1, 0x31);
  const __m256 s10 = _mm256_permute2f128_ps(b0, b1, 0x20), s11 = _mm256_permute2f128_ps(b0, b1, 0x31);
  const __m256 l1 = _mm256_set_m128(_mm_set1_ps(lw[x + 1]), _mm_set1_ps(lw[x]));
  const __m256 n1 = _mm256_set_m128(_mm_set1_ps(nu_w[x + 1]), _mm_set1_ps(nu_w[x]));
  const __m256 l0 = _mm256_sub_ps(one, l1), n0 = _mm256_sub_ps(one, n1);
  const __m256 ra = _mm256_add_ps(_mm256_mul_ps(l0, s00), _mm256_mul_ps(l1, s01));
  const __m256 rb = _mm256_add_ps(_mm256_mul_ps(l0, s10), _mm256_mul_ps(l1, s11));
  const __m256 L = _mm256_add_ps(_mm256_mul_ps(n0, ra), _mm256_mul_ps(n1, rb));
  _mm256_storeu_ps(sum[x].v, _mm256_add_ps(_mm256_loadu_ps(sum[x].v), _mm256_mul_ps(ws, L)));
}

// The taps run kAhead texels ahead of the reads, so that the reads do not
// wait on the divider's latency and the two overlap.
constexpr int kAhead = 16;

SKYBAKE_AVX2 int add_node_row_avx2(const NodeRow& q, const MuSAxis::Constants& c,
                                   const Rgb4* slice, const Rgb4& wS, int n, Rgb4* sum) {
  const NodeLanes k{_mm256_set1_pd(q.r),       _mm256_set1_pd(q.s),     _mm256_set1_pd(q.inv_r_i),
                    _mm256_set1_pd(1.0),       _mm256_setzero_pd(),     _mm256_set1_pd(-c.rb),
                    _mm256_set1_pd(c.rb2),     _mm256_set1_pd(c.H2),    _mm256_set1_pd(c.d_min),
                    _mm256_set1_pd(c.inv_span), _mm256_set1_pd(c.inv_A),
                    _mm256_set1_pd(double(c.size - 1)), _mm256_set1_pd(double(c.size - 2)),
                    c.mu_s_min};
  const __m256 ws = _mm256_set_m128(_mm_load_ps(wS.v), _mm_load_ps(wS.v));
  const int done = n / 4 * 4;
  int* at0 = q.at0;
  int* at1 = q.at1;
  float* lw = q.lw;
  for (int x = 0; x < std::min(kAhead, done); x += 4) node_taps(k, q, x, at0, at1, lw);
  for (int x = 0; x < done; x += 4) {
    if (x + kAhead < done) node_taps(k, q, x + kAhead, at0, at1, lw);
    node_reads(slice, at0, at1, lw, q.nu_w, ws, x, sum);
    node_reads(slice, at0, at1, lw, q.nu_w, ws, x + 2, sum);
  }
  return done;
}
#endif

}  // namespace

int add_node_row(const NodeRow& row, const MuSAxis& axis, const Rgb4* slice, const Rgb4& wS, int n,
                 Rgb4* sum) {
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) return add_node_row_avx2(row, axis.constants(), slice, wS, n, sum);
#endif
  (void)row, (void)axis, (void)slice, (void)wS, (void)n, (void)sum;
  return 0;
}

}  // namespace skybake

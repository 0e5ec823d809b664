// The loop of one node of a multiple-scattering row, in AVX2, SSE2 and plain
// C++ (for CPUs without SSE2). See the header.
#include "atmosphere/kernels/node_slice_reads.hpp"

#include <algorithm>
#include <cmath>

#include "core/wide_intrinsics.hpp"

namespace skybake {

SunCosineTapsFloat::SunCosineTapsFloat(const MuSAxis::Constants& c) {
  const double A = 1.0 / c.inv_A, span = 1.0 / c.inv_span;
  lo = float(std::max(-1.0, c.mu_s_min));
  h2 = float(c.H2 / c.rb2);
  k1 = float((A * span + c.d_min) / c.rb);
  ak2 = float(A * (span - c.d_min) / c.rb);
  ah2 = float(A * c.H2 / c.rb2);
  last = float(c.size - 1);
  below_last = float(c.size - 2);
}

// std::max(v, lo) is _mm_max_ps(lo, v) and std::min(v, hi) _mm_min_ps(hi,
// v) for every non-NaN v, signed zeros included: the lanes' operations.
void SunCosineTapsFloat::tap(double mu_s, int& i0, float& w) const {
  const float m = std::min(std::max(float(mu_s), lo), 1.0f);
  const float D = m + std::sqrt(m * m + h2);
  const float u = std::min(std::max(D * k1 - h2, 0.0f) / (D * ak2 + ah2), 1.0f);
  const float t = u * last;
  const float i = std::min(float(int(t)), below_last);
  w = t - i;
  i0 = int(i);
}

namespace {

// The cosine at the node of one texel, in double (as single scattering's
// SingleScatteringRay::at_suns): the product by 1 / r_i, not a division.
[[maybe_unused]] inline double node_cosine(const NodeRow& q, int x) {
  return (q.r * q.mu_s[x] + q.s * q.nu[x]) * q.inv_r_i;
}

#if defined(__SSE2__)
// SunCosineTapsFloat::tap of the four texels from x, and their reads' texels.
inline void node_taps_sse2(const SunCosineTapsFloat& k, const NodeRow& q, int x) {
  const __m128d r = _mm_set1_pd(q.r), s = _mm_set1_pd(q.s), inv_r_i = _mm_set1_pd(q.inv_r_i);
  auto cosines = [&](int from) {
    return _mm_cvtpd_ps(_mm_mul_pd(
        _mm_add_pd(_mm_mul_pd(r, _mm_loadu_pd(q.mu_s + from)), _mm_mul_pd(s, _mm_loadu_pd(q.nu + from))),
        inv_r_i));
  };
  const __m128 one = _mm_set1_ps(1.0f), h2 = _mm_set1_ps(k.h2);
  const __m128 m = _mm_min_ps(one, _mm_max_ps(_mm_set1_ps(k.lo), _mm_movelh_ps(cosines(x), cosines(x + 2))));
  const __m128 D = _mm_add_ps(m, _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(m, m), h2)));
  const __m128 N = _mm_max_ps(_mm_setzero_ps(), _mm_sub_ps(_mm_mul_ps(D, _mm_set1_ps(k.k1)), h2));
  const __m128 Q = _mm_add_ps(_mm_mul_ps(D, _mm_set1_ps(k.ak2)), _mm_set1_ps(k.ah2));
  const __m128 t = _mm_mul_ps(_mm_min_ps(one, _mm_div_ps(N, Q)), _mm_set1_ps(k.last));
  const __m128 i = _mm_min_ps(_mm_set1_ps(k.below_last), _mm_cvtepi32_ps(_mm_cvttps_epi32(t)));
  _mm_storeu_ps(q.lw + x, _mm_sub_ps(t, i));
  const __m128i tap = _mm_cvttps_epi32(i);
  auto plus = [&](const int* offset) {
    return _mm_add_epi32(tap, _mm_loadu_si128(reinterpret_cast<const __m128i*>(offset + x)));
  };
  _mm_storeu_si128(reinterpret_cast<__m128i*>(q.at0 + x), plus(q.nu_i0));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(q.at1 + x), plus(q.nu_i1));
}

// The read of texel x: sum += wS lerp(lerp(s00, s01, lw), lerp(s10, s11, lw), nw).
inline void node_read_sse2(const Rgb4* slice, const NodeRow& q, const Rgb4& wS, int x, Rgb4& sum) {
  const Rgb4* s0 = slice + q.at0[x];
  const Rgb4* s1 = slice + q.at1[x];
  const float lw = q.lw[x], nw = q.nu_w[x];
  const __m128 l1 = _mm_set1_ps(lw), l0 = _mm_set1_ps(1.0f - lw);
  const __m128 n1 = _mm_set1_ps(nw), n0 = _mm_set1_ps(1.0f - nw);
  const __m128 a = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s0[0].v)), _mm_mul_ps(l1, _mm_load_ps(s0[1].v)));
  const __m128 b = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s1[0].v)), _mm_mul_ps(l1, _mm_load_ps(s1[1].v)));
  const __m128 L = _mm_add_ps(_mm_mul_ps(n0, a), _mm_mul_ps(n1, b));
  _mm_store_ps(sum.v, _mm_add_ps(_mm_load_ps(sum.v), _mm_mul_ps(_mm_load_ps(wS.v), L)));
}

// node_read_sse2 of a texel that reads one nu slice (NodeRow::single).
inline void node_read_one_sse2(const Rgb4* slice, const NodeRow& q, const Rgb4& wS, int x,
                               Rgb4& sum) {
  const Rgb4* s0 = slice + q.at0[x];
  const float lw = q.lw[x];
  const __m128 l1 = _mm_set1_ps(lw), l0 = _mm_set1_ps(1.0f - lw);
  const __m128 a = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s0[0].v)), _mm_mul_ps(l1, _mm_load_ps(s0[1].v)));
  _mm_store_ps(sum.v, _mm_add_ps(_mm_load_ps(sum.v), _mm_mul_ps(_mm_load_ps(wS.v), a)));
}
#else
inline void node_read_plain(const Rgb4* slice, const NodeRow& q, const Rgb4& wS, int x, Rgb4& sum) {
  const Rgb4* s0 = slice + q.at0[x];
  const Rgb4* s1 = slice + q.at1[x];
  const float lw = q.lw[x], nw = q.nu_w[x];
  const bool one = x < q.single;
  for (int c = 0; c < 4; ++c) {
    const float a = (1.0f - lw) * s0[0].v[c] + lw * s0[1].v[c];
    const float b = (1.0f - lw) * s1[0].v[c] + lw * s1[1].v[c];
    sum.v[c] += wS.v[c] * (one ? a : (1.0f - nw) * a + nw * b);
  }
}
#endif

#if SKYBAKE_HAS_AVX2
// The reads below are inlined into the AVX-512 loop too, whose options
// differ (core/simd_switches.hpp).
#define SKYBAKE_INLINE inline __attribute__((always_inline))

// node_taps_sse2 for the eight texels from x.
struct NodeLanes {
  __m256d r, s, inv_r_i;
  __m256 lo, one, zero, h2, k1, ak2, ah2, last, below_last;
};

// Four texels' cosines at the node, rounded to float.
SKYBAKE_AVX2 inline __m128 node_cosines_avx2(const NodeLanes& k, const NodeRow& q, int x) {
  return _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(k.r, _mm256_loadu_pd(q.mu_s + x)),
                                                     _mm256_mul_pd(k.s, _mm256_loadu_pd(q.nu + x))),
                                       k.inv_r_i));
}

SKYBAKE_AVX2 inline void node_taps_avx2(const NodeLanes& k, const NodeRow& q, int x) {
  const __m256 c = _mm256_set_m128(node_cosines_avx2(k, q, x + 4), node_cosines_avx2(k, q, x));
  const __m256 m = _mm256_min_ps(k.one, _mm256_max_ps(k.lo, c));
  const __m256 D = _mm256_add_ps(m, _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(m, m), k.h2)));
  const __m256 N = _mm256_max_ps(k.zero, _mm256_sub_ps(_mm256_mul_ps(D, k.k1), k.h2));
  const __m256 Q = _mm256_add_ps(_mm256_mul_ps(D, k.ak2), k.ah2);
  const __m256 t = _mm256_mul_ps(_mm256_min_ps(k.one, _mm256_div_ps(N, Q)), k.last);
  const __m256 i = _mm256_min_ps(k.below_last, _mm256_cvtepi32_ps(_mm256_cvttps_epi32(t)));
  _mm256_storeu_ps(q.lw + x, _mm256_sub_ps(t, i));
  const __m256i tap = _mm256_cvttps_epi32(i);
  const __m256i* i0 = reinterpret_cast<const __m256i*>(q.nu_i0 + x);
  const __m256i* i1 = reinterpret_cast<const __m256i*>(q.nu_i1 + x);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(q.at0 + x), _mm256_add_epi32(tap, _mm256_loadu_si256(i0)));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(q.at1 + x), _mm256_add_epi32(tap, _mm256_loadu_si256(i1)));
}

// node_read_sse2 for texels x and x + 1: a 256-bit load takes a texel's s00
// and s01 (or s10 and s11) together, regrouped into (s00 of x, s00 of
// x + 1) and (s01 of x, s01 of x + 1).
SKYBAKE_AVX2 SKYBAKE_INLINE void node_reads_avx2(const Rgb4* slice, const NodeRow& q, __m256 ws, int x,
                                         Rgb4* sum) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const int *at0 = q.at0, *at1 = q.at1;
  const __m256 a0 = _mm256_loadu_ps(slice[at0[x]].v), a1 = _mm256_loadu_ps(slice[at0[x + 1]].v);
  const __m256 b0 = _mm256_loadu_ps(slice[at1[x]].v), b1 = _mm256_loadu_ps(slice[at1[x + 1]].v);
  const __m256 s00 = _mm256_permute2f128_ps(a0, a1, 0x20), s01 = _mm256_permute2f128_ps(a0, a1, 0x31);
  const __m256 s10 = _mm256_permute2f128_ps(b0, b1, 0x20), s11 = _mm256_permute2f128_ps(b0, b1, 0x31);
  const __m256 l1 = _mm256_set_m128(_mm_set1_ps(q.lw[x + 1]), _mm_set1_ps(q.lw[x]));
  const __m256 n1 = _mm256_set_m128(_mm_set1_ps(q.nu_w[x + 1]), _mm_set1_ps(q.nu_w[x]));
  const __m256 l0 = _mm256_sub_ps(one, l1), n0 = _mm256_sub_ps(one, n1);
  const __m256 ra = _mm256_add_ps(_mm256_mul_ps(l0, s00), _mm256_mul_ps(l1, s01));
  const __m256 rb = _mm256_add_ps(_mm256_mul_ps(l0, s10), _mm256_mul_ps(l1, s11));
  const __m256 L = _mm256_add_ps(_mm256_mul_ps(n0, ra), _mm256_mul_ps(n1, rb));
  _mm256_storeu_ps(sum[x].v, _mm256_add_ps(_mm256_loadu_ps(sum[x].v), _mm256_mul_ps(ws, L)));
}

// node_reads_avx2 of two texels that read one nu slice (NodeRow::single).
SKYBAKE_AVX2 SKYBAKE_INLINE void node_reads_one_avx2(const Rgb4* slice, const NodeRow& q, __m256 ws, int x,
                                             Rgb4* sum) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 a0 = _mm256_loadu_ps(slice[q.at0[x]].v), a1 = _mm256_loadu_ps(slice[q.at0[x + 1]].v);
  const __m256 s00 = _mm256_permute2f128_ps(a0, a1, 0x20), s01 = _mm256_permute2f128_ps(a0, a1, 0x31);
  const __m256 l1 = _mm256_set_m128(_mm_set1_ps(q.lw[x + 1]), _mm_set1_ps(q.lw[x]));
  const __m256 l0 = _mm256_sub_ps(one, l1);
  const __m256 ra = _mm256_add_ps(_mm256_mul_ps(l0, s00), _mm256_mul_ps(l1, s01));
  _mm256_storeu_ps(sum[x].v, _mm256_add_ps(_mm256_loadu_ps(sum[x].v), _mm256_mul_ps(ws, ra)));
}

// The taps run kAhead texels ahead of the reads, so that the reads do not
// wait on the divider's latency and the two overlap.
constexpr int kAhead = 16;

SKYBAKE_AVX2 void node_row_avx2(const NodeRow& q, const SunCosineTapsFloat& c, const Rgb4* slice,
                                const Rgb4& wS, int end, Rgb4* sum) {
  const NodeLanes k{_mm256_set1_pd(q.r),       _mm256_set1_pd(q.s),    _mm256_set1_pd(q.inv_r_i),
                    _mm256_set1_ps(c.lo),      _mm256_set1_ps(1.0f),   _mm256_setzero_ps(),
                    _mm256_set1_ps(c.h2),      _mm256_set1_ps(c.k1),   _mm256_set1_ps(c.ak2),
                    _mm256_set1_ps(c.ah2),     _mm256_set1_ps(c.last), _mm256_set1_ps(c.below_last)};
  const __m256 ws = _mm256_set_m128(_mm_load_ps(wS.v), _mm_load_ps(wS.v));
  for (int x = 0; x < std::min(kAhead, end); x += 8) node_taps_avx2(k, q, x);
  for (int x = 0; x < end; x += 8) {
    if (x + kAhead < end) node_taps_avx2(k, q, x + kAhead);
    if (x < q.single)
      for (int j = 0; j < 8; j += 2) node_reads_one_avx2(slice, q, ws, x + j, sum);
    else
      for (int j = 0; j < 8; j += 2) node_reads_avx2(slice, q, ws, x + j, sum);
  }
}
#endif

#if defined(SKYBAKE_AVX512)
SKYBAKE_AVX512_WARNINGS_OFF
struct NodeLanes512 {
  __m512d r, s, inv_r_i;
  __m512 lo, one, zero, h2, k1, ak2, ah2, last, below_last;
};

// node_taps_avx2 for the sixteen texels from x.
SKYBAKE_AVX512 inline void node_taps_avx512(const NodeLanes512& k, const NodeRow& q, int x) {
  __m256 half[2];
  for (int h = 0; h < 2; ++h) {
    const __m512d mu_s = _mm512_loadu_pd(q.mu_s + x + 8 * h), nu = _mm512_loadu_pd(q.nu + x + 8 * h);
    half[h] = _mm512_cvtpd_ps(
        _mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(k.r, mu_s), _mm512_mul_pd(k.s, nu)), k.inv_r_i));
  }
  const __m512 c = _mm512_insertf32x8(_mm512_castps256_ps512(half[0]), half[1], 1);
  const __m512 m = _mm512_min_ps(k.one, _mm512_max_ps(k.lo, c));
  const __m512 D = _mm512_add_ps(m, _mm512_sqrt_ps(_mm512_add_ps(_mm512_mul_ps(m, m), k.h2)));
  const __m512 N = _mm512_max_ps(k.zero, _mm512_sub_ps(_mm512_mul_ps(D, k.k1), k.h2));
  const __m512 Q = _mm512_add_ps(_mm512_mul_ps(D, k.ak2), k.ah2);
  const __m512 t = _mm512_mul_ps(_mm512_min_ps(k.one, _mm512_div_ps(N, Q)), k.last);
  const __m512 i = _mm512_min_ps(k.below_last, _mm512_cvtepi32_ps(_mm512_cvttps_epi32(t)));
  _mm512_storeu_ps(q.lw + x, _mm512_sub_ps(t, i));
  const __m512i tap = _mm512_cvttps_epi32(i);
  _mm512_storeu_si512(q.at0 + x, _mm512_add_epi32(tap, _mm512_loadu_si512(q.nu_i0 + x)));
  _mm512_storeu_si512(q.at1 + x, _mm512_add_epi32(tap, _mm512_loadu_si512(q.nu_i1 + x)));
}

// node_row_avx2 with the taps of sixteen texels per step (the square root
// and the division at twice the lanes); the reads are node_row_avx2's. The
// taps of a last group may run past `end` (RowTexels' arrays hold 16 more
// texels) on valid texels.
SKYBAKE_AVX512 void node_row_avx512(const NodeRow& q, const SunCosineTapsFloat& c, const Rgb4* slice,
                                    const Rgb4& wS, int end, Rgb4* sum) {
  const NodeLanes512 k{_mm512_set1_pd(q.r),    _mm512_set1_pd(q.s),    _mm512_set1_pd(q.inv_r_i),
                       _mm512_set1_ps(c.lo),   _mm512_set1_ps(1.0f),   _mm512_setzero_ps(),
                       _mm512_set1_ps(c.h2),   _mm512_set1_ps(c.k1),   _mm512_set1_ps(c.ak2),
                       _mm512_set1_ps(c.ah2),  _mm512_set1_ps(c.last), _mm512_set1_ps(c.below_last)};
  const __m256 ws = _mm256_set_m128(_mm_load_ps(wS.v), _mm_load_ps(wS.v));
  constexpr int kAhead16 = 32;
  for (int x = 0; x < std::min(kAhead16, end); x += 16) node_taps_avx512(k, q, x);
  for (int x = 0; x < end; x += 16) {
    if (x + kAhead16 < end) node_taps_avx512(k, q, x + kAhead16);
    for (int j = x; j < std::min(x + 16, end); j += 2) {
      if (j < q.single)
        node_reads_one_avx2(slice, q, ws, j, sum);
      else
        node_reads_avx2(slice, q, ws, j, sum);
    }
  }
}
SKYBAKE_AVX512_WARNINGS_ON
#endif

}  // namespace

void add_node_slice_reads(const NodeRow& row, const SunCosineTapsFloat& taps, const Rgb4* slice, const Rgb4& wS,
                  int end, Rgb4* sum) {
#if defined(SKYBAKE_AVX512)
  if (avx512_enabled()) {
    node_row_avx512(row, taps, slice, wS, end, sum);
    return;
  }
#endif
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) {
    node_row_avx2(row, taps, slice, wS, end, sum);
    return;
  }
#endif
#if defined(__SSE2__)
  for (int x = 0; x < end; x += 4) node_taps_sse2(taps, row, x);
  for (int x = 0; x < row.single; ++x) node_read_one_sse2(slice, row, wS, x, sum[x]);
  for (int x = row.single; x < end; ++x) node_read_sse2(slice, row, wS, x, sum[x]);
#else
  for (int x = 0; x < end; ++x) {
    int i0 = 0;
    taps.tap(node_cosine(row, x), i0, row.lw[x]);
    row.at0[x] = i0 + row.nu_i0[x];
    row.at1[x] = i0 + row.nu_i1[x];
  }
  for (int x = 0; x < end; ++x) node_read_plain(slice, row, wS, x, sum[x]);
#endif
}

}  // namespace skybake

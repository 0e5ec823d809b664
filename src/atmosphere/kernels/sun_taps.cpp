// The taps of a whole texel row at once, for the bakers' hottest loops
// (single scattering's transmittance to the sun, the orders' mu_s taps):
// SSE2, two doubles at a time, with no branch, where one tap at a time
// mispredicted its clamps and could not be vectorized (std::sqrt sets errno).
// MuSAxis::taps also has an AVX2 twin, four doubles at a time, used where the
// CPU has it (core/simd_switches.hpp): the same operations per lane, so the
// same values. Every value equals the one-at-a-time function's: _mm_max_pd(b, a) is
// std::max(a, b) (b > a ? b : a) and _mm_min_pd(b, a) is std::min(a, b),
// signed zeros included, and std::clamp(v, lo, hi) is
// std::min(std::max(v, lo), hi) for every non-NaN v.
#include "atmosphere/kernels/sun_taps.hpp"

#include <algorithm>

#include "core/wide_intrinsics.hpp"

namespace skybake {

namespace {

#if defined(__SSE2__)
// Texel-centre taps of x in [0, 1] over n_texels: i0 = min(int(t), n - 2),
// w = t - i0, t = x (n - 1).
inline void store_taps(__m128d x, int n_texels, int* i0, double* w) {
  const __m128d t = _mm_mul_pd(x, _mm_set1_pd(double(n_texels - 1)));
  const __m128d i = _mm_min_pd(_mm_set1_pd(double(n_texels - 2)), _mm_cvtepi32_pd(_mm_cvttpd_epi32(t)));
  _mm_storeu_pd(w, _mm_sub_pd(t, i));
  alignas(16) int lanes[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(lanes), _mm_cvttpd_epi32(i));
  i0[0] = lanes[0];
  i0[1] = lanes[1];
}

inline __m128d clamp_pd(__m128d v, double lo, double hi) {
  return _mm_min_pd(_mm_set1_pd(hi), _mm_max_pd(_mm_set1_pd(lo), v));
}
#endif

#if SKYBAKE_HAS_AVX2
// MuSAxis::taps' loop, four cosines at a time; returns how many it did.
SKYBAKE_AVX2 int mu_s_taps_avx2(const double* mu_s, int n, int* i0, double* w, double mu_s_min,
                                double rb, double rb2, double H2, double d_min, double inv_span,
                                double inv_A, int size) {
  const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
  const __m256d minus_rb = _mm256_set1_pd(-rb), rb2_4 = _mm256_set1_pd(rb2);
  const __m256d H2_4 = _mm256_set1_pd(H2), d_min4 = _mm256_set1_pd(d_min);
  const __m256d inv_span4 = _mm256_set1_pd(inv_span), inv_A4 = _mm256_set1_pd(inv_A);
  const __m256d last = _mm256_set1_pd(double(size - 1)), below_last = _mm256_set1_pd(double(size - 2));
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m256d m = clamp_lanes(_mm256_loadu_pd(mu_s + k), mu_s_min, 1.0);
    const __m256d root = _mm256_sqrt_pd(
        _mm256_max_pd(zero, _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(rb2_4, m), m), H2_4)));
    const __m256d d = _mm256_add_pd(_mm256_mul_pd(minus_rb, m), root);
    const __m256d a = _mm256_mul_pd(_mm256_sub_pd(d, d_min4), inv_span4);
    const __m256d x = _mm256_div_pd(
        _mm256_max_pd(zero, _mm256_sub_pd(one, _mm256_mul_pd(a, inv_A4))), _mm256_add_pd(one, a));
    // store_taps
    const __m256d t = _mm256_mul_pd(clamp_lanes(x, 0.0, 1.0), last);
    const __m256d i = _mm256_min_pd(below_last, _mm256_cvtepi32_pd(_mm256_cvttpd_epi32(t)));
    _mm256_storeu_pd(w + k, _mm256_sub_pd(t, i));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(i0 + k), _mm256_cvttpd_epi32(i));
  }
  return k;
}

// TransmittanceReader::add_sun_products four cosines at a time: sun_taps'
// operations (in their SSE2 order) and to_sun_at's; returns how many it
// did. (Gathers were slower here than loads and a transpose.)
struct SunRow {
  const float *row0, *row1;
  double r, rt, d_min, inv_span, sun_edge, inv_sun_width, wy;
  int width, stride;
};
SKYBAKE_AVX2 int sun_products_avx2(const SunRow& q, const double* mu_s, int n, const double a[6],
                                   double* const sums[6], int* i0, double* wt, double* vis) {
  const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd(), three = _mm256_set1_pd(3.0),
                two = _mm256_set1_pd(2.0);
  const __m256d minus_r = _mm256_set1_pd(-q.r);
  const __m256d rr = _mm256_set1_pd(q.r * q.r), tt = _mm256_set1_pd(q.rt * q.rt);
  const __m256d d_min = _mm256_set1_pd(q.d_min), inv_span = _mm256_set1_pd(q.inv_span);
  const __m256d edge = _mm256_set1_pd(q.sun_edge), inv_width = _mm256_set1_pd(q.inv_sun_width);
  const __m256d last = _mm256_set1_pd(double(q.width - 1));
  const __m256d below_last = _mm256_set1_pd(double(q.width - 2)), wy = _mm256_set1_pd(q.wy);
  const int count = n / 4 * 4;
  // First every sun's taps and visible fraction (the square roots), then
  // the reads: in one loop each read waited on its square root's latency.
  for (int k = 0; k < count; k += 4) {
    const __m256d raw = _mm256_loadu_pd(mu_s + k);
    const __m256d mu = clamp_lanes(raw, -1.0, 1.0);
    const __m256d discriminant =
        _mm256_add_pd(_mm256_mul_pd(rr, _mm256_sub_pd(_mm256_mul_pd(mu, mu), one)), tt);
    const __m256d d = _mm256_max_pd(
        _mm256_add_pd(_mm256_mul_pd(minus_r, mu), _mm256_sqrt_pd(_mm256_max_pd(zero, discriminant))),
        zero);
    const __m256d x = clamp_lanes(_mm256_mul_pd(_mm256_sub_pd(d, d_min), inv_span), 0.0, 1.0);
    const __m256d t = _mm256_mul_pd(x, last);
    const __m256d i = _mm256_min_pd(below_last, _mm256_cvtepi32_pd(_mm256_cvttpd_epi32(t)));
    _mm256_storeu_pd(wt + k, _mm256_sub_pd(t, i));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(i0 + k), _mm256_cvttpd_epi32(i));
    const __m256d s = _mm256_mul_pd(_mm256_sub_pd(raw, edge), inv_width);
    const __m256d smooth = _mm256_mul_pd(_mm256_mul_pd(s, s), _mm256_sub_pd(three, _mm256_mul_pd(two, s)));
    const __m256d full = _mm256_cmp_pd(s, one, _CMP_GE_OQ), none = _mm256_cmp_pd(s, zero, _CMP_LE_OQ);
    _mm256_storeu_pd(vis + k, _mm256_or_pd(_mm256_and_pd(full, one),
                                           _mm256_andnot_pd(_mm256_or_pd(full, none), smooth)));
  }
  for (int k = 0; k < count; k += 4) {
    const __m256d visible = _mm256_loadu_pd(vis + k);
    // A sun below the horizon at this node for all four: T = 0 adds +0 to
    // sums that are >= +0, which leaves them as they are.
    if (_mm256_movemask_pd(_mm256_cmp_pd(visible, zero, _CMP_NEQ_UQ)) == 0) continue;
    const __m256d w = _mm256_loadu_pd(wt + k);
    // Each lane's texels i0 and i0 + 1 of both LUT rows: R G B at positions
    // 0-2 of a load at the first and 1-3 of a load ending at the second's
    // blue (any stride >= 3, never past the row), transposed into lanes.
    const int* at = i0 + k;
    __m128 lo[2][4], hi[2][4];
    for (int y = 0; y < 2; ++y) {
      const float* row = y == 0 ? q.row0 : q.row1;
      for (int l = 0; l < 4; ++l) {
        lo[y][l] = _mm_loadu_ps(row + q.stride * at[l]);
        hi[y][l] = _mm_loadu_ps(row + q.stride * at[l] + q.stride - 1);
      }
      _MM_TRANSPOSE4_PS(lo[y][0], lo[y][1], lo[y][2], lo[y][3]);
      _MM_TRANSPOSE4_PS(hi[y][0], hi[y][1], hi[y][2], hi[y][3]);
    }
    for (int c = 0; c < 3; ++c) {
      const __m256d t00 = _mm256_cvtps_pd(lo[0][c]), t10 = _mm256_cvtps_pd(hi[0][c + 1]);
      const __m256d t01 = _mm256_cvtps_pd(lo[1][c]), t11 = _mm256_cvtps_pd(hi[1][c + 1]);
      const __m256d bottom = _mm256_add_pd(t00, _mm256_mul_pd(_mm256_sub_pd(t10, t00), w));
      const __m256d top = _mm256_add_pd(t01, _mm256_mul_pd(_mm256_sub_pd(t11, t01), w));
      const __m256d T = _mm256_mul_pd(
          visible, _mm256_add_pd(bottom, _mm256_mul_pd(_mm256_sub_pd(top, bottom), wy)));
      for (int g = 0; g < 2; ++g) {
        double* sum = sums[3 * g + c] + k;
        _mm256_storeu_pd(sum, _mm256_add_pd(_mm256_loadu_pd(sum),
                                            _mm256_mul_pd(_mm256_set1_pd(a[3 * g + c]), T)));
      }
    }
  }
  return count;
}
#endif

}  // namespace

int add_sun_products(const SunTapTable& table, const TransmittanceReader::Row& row,
                     const double* mu_s, int n, const glm::dvec3& a_rayleigh,
                     const glm::dvec3& a_mie, double* const sums[6], int* i0, double* w,
                     double* visible) {
#if SKYBAKE_HAS_AVX2
  if (!avx2_enabled() || table.stride < 3) return 0;
  const SunRow q{row.row0,    row.row1,  row.r,         table.rt,    row.d_min, row.inv_span,
                 row.sun_edge, row.inv_sun_width, row.wy, table.width, table.stride};
  const double a[6] = {a_rayleigh.r, a_rayleigh.g, a_rayleigh.b, a_mie.r, a_mie.g, a_mie.b};
  return sun_products_avx2(q, mu_s, n, a, sums, i0, w, visible);
#else
  (void)table, (void)row, (void)mu_s, (void)n, (void)a_rayleigh, (void)a_mie, (void)sums, (void)i0, (void)w,
      (void)visible;
  return 0;
#endif
}

int mu_s_taps(const MuSAxis::Constants& c, const double* mu_s, int n, int* i0, double* w) {
  int k = 0;
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled())
    k = mu_s_taps_avx2(mu_s, n, i0, w, c.mu_s_min, c.rb, c.rb2, c.H2, c.d_min, c.inv_span, c.inv_A,
                       c.size);
#endif
#if defined(__SSE2__)
  const __m128d one = _mm_set1_pd(1.0), zero = _mm_setzero_pd();
  const __m128d minus_rb = _mm_set1_pd(-c.rb), rb2 = _mm_set1_pd(c.rb2), H2 = _mm_set1_pd(c.H2);
  const __m128d d_min = _mm_set1_pd(c.d_min), inv_span = _mm_set1_pd(c.inv_span);
  const __m128d inv_A = _mm_set1_pd(c.inv_A);
  for (; k + 2 <= n; k += 2) {
    const __m128d m = clamp_pd(_mm_loadu_pd(mu_s + k), c.mu_s_min, 1.0);
    const __m128d root =
        _mm_sqrt_pd(_mm_max_pd(zero, _mm_add_pd(_mm_mul_pd(_mm_mul_pd(rb2, m), m), H2)));
    const __m128d d = _mm_add_pd(_mm_mul_pd(minus_rb, m), root);
    const __m128d a = _mm_mul_pd(_mm_sub_pd(d, d_min), inv_span);
    const __m128d x = _mm_div_pd(_mm_max_pd(zero, _mm_sub_pd(one, _mm_mul_pd(a, inv_A))),
                                 _mm_add_pd(one, a));
    store_taps(clamp_pd(x, 0.0, 1.0), c.size, i0 + k, w + k);
  }
#endif
  return k;
}

int sun_taps(const SunTapTable& table, const TransmittanceReader::Row& row, const double* mu_s,
              int n, int* i0, double* w, double* visible) {
  int k = 0;
#if defined(__SSE2__)
  const __m128d one = _mm_set1_pd(1.0), zero = _mm_setzero_pd(), three = _mm_set1_pd(3.0),
                two = _mm_set1_pd(2.0);
  const __m128d minus_r = _mm_set1_pd(-row.r);
  const __m128d rr = _mm_set1_pd(row.r * row.r), tt = _mm_set1_pd(table.rt * table.rt);
  const __m128d d_min = _mm_set1_pd(row.d_min), inv_span = _mm_set1_pd(row.inv_span);
  const __m128d edge = _mm_set1_pd(row.sun_edge), inv_width = _mm_set1_pd(row.inv_sun_width);
  for (; k + 2 <= n; k += 2) {
    const __m128d raw = _mm_loadu_pd(mu_s + k);
    const __m128d mu = clamp_pd(raw, -1.0, 1.0);
    // distance_to_top_boundary, then to_top's x_mu.
    const __m128d discriminant = _mm_add_pd(_mm_mul_pd(rr, _mm_sub_pd(_mm_mul_pd(mu, mu), one)), tt);
    const __m128d d = _mm_max_pd(_mm_add_pd(_mm_mul_pd(minus_r, mu),
                                            _mm_sqrt_pd(_mm_max_pd(zero, discriminant))),
                                 zero);
    store_taps(clamp_pd(_mm_mul_pd(_mm_sub_pd(d, d_min), inv_span), 0.0, 1.0), table.width,
               i0 + k, w + k);
    // to_sun's smoothstep: 1 at t >= 1, 0 at t <= 0.
    const __m128d t = _mm_mul_pd(_mm_sub_pd(raw, edge), inv_width);
    const __m128d smooth = _mm_mul_pd(_mm_mul_pd(t, t), _mm_sub_pd(three, _mm_mul_pd(two, t)));
    const __m128d full = _mm_cmpge_pd(t, one), none = _mm_cmple_pd(t, zero);
    const __m128d v = _mm_or_pd(_mm_and_pd(full, one), _mm_andnot_pd(_mm_or_pd(full, none), smooth));
    _mm_storeu_pd(visible + k, v);
  }
#endif
  return k;
}

}  // namespace skybake

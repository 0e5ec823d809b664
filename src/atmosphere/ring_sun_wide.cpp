#include "atmosphere/ring_sun_wide.hpp"

#include <algorithm>

#include "atmosphere/wide_lookups.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
// transmittance_at_radius's fields in the lanes of four samples.
struct RadiusLanes {
  __m256d r, d_min, span, fy;  // span: d_max - d_min
  __m128i row0, row1;          // offsets (floats) of the rows around v(r)
};

SKYBAKE_AVX2 RadiusLanes radius_lanes(const Texture& lut, const Atmosphere& atm, __m256d radius) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double horizon = safe_sqrt((rt - rb) * (rt + rb));  // horizon_distance
  RadiusLanes l;
  l.r = clamp_lanes(radius, rb, rt);
  const __m256d rho = _mm256_sqrt_pd(_mm256_max_pd(
      _mm256_setzero_pd(), _mm256_mul_pd(_mm256_sub_pd(l.r, _mm256_set1_pd(rb)),
                                         _mm256_add_pd(l.r, _mm256_set1_pd(rb)))));
  const int h = lut.height;
  const __m256d v = _mm256_add_pd(
      _mm256_set1_pd(0.5 / h),
      _mm256_mul_pd(_mm256_div_pd(rho, _mm256_set1_pd(horizon)), _mm256_set1_pd(1.0 - 1.0 / h)));
  const AxisLanes ay = bilinear_axis_lanes(h, lut.width * lut.channel_count(), v);
  l.row0 = ay.o0;
  l.row1 = ay.o1;
  l.fy = ay.f;
  l.d_min = _mm256_sub_pd(_mm256_set1_pd(rt), l.r);
  l.span = _mm256_sub_pd(_mm256_add_pd(rho, _mm256_set1_pd(horizon)), l.d_min);
  return l;
}

// texel_lanes (wide_lookups.hpp) by one 128-bit load a texel, its three
// floats and the next, transposed: the same floats widened the same way.
// `last` is the offset of the table's last texel, which is loaded masked.
SKYBAKE_AVX2 inline RgbTexelLanes texel_lanes_loaded(const float* data, __m128i o, int last) {
  alignas(16) int off[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(off), o);
  __m128 t[4];
  for (int k = 0; k < 4; ++k)
    t[k] = off[k] < last ? _mm_loadu_ps(data + off[k])
                         : _mm_maskload_ps(data + off[k], _mm_setr_epi32(-1, -1, -1, 0));
  _MM_TRANSPOSE4_PS(t[0], t[1], t[2], t[3]);
  return {{_mm256_cvtps_pd(t[0]), _mm256_cvtps_pd(t[1]), _mm256_cvtps_pd(t[2])}};
}

// lookup_sun_transmittance(lut, at, rb, mu) in each lane, `at` the lane's
// RadiusLanes, mu already clamped; adds each channel to sum[c].
SKYBAKE_AVX2 void add_sun_lanes(const Texture& lut, const Atmosphere& atm, const RadiusLanes& at,
                                __m256d mu, __m256d sum[3]) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const __m256d zero = _mm256_setzero_pd();
  const __m256d rr_mm1 =
      _mm256_mul_pd(_mm256_mul_pd(at.r, at.r), _mm256_sub_pd(_mm256_mul_pd(mu, mu), _mm256_set1_pd(1.0)));
  const __m256d ground = _mm256_and_pd(
      _mm256_cmp_pd(mu, zero, _CMP_LT_OQ),
      _mm256_cmp_pd(_mm256_add_pd(rr_mm1, _mm256_set1_pd(rb * rb)), zero, _CMP_GE_OQ));
  // Every lane in the planet's shadow: each would add +0 (the masked read).
  if (_mm256_movemask_pd(ground) == 0xF) return;
  const __m256d d = _mm256_max_pd(  // distance_to_top_boundary
      _mm256_add_pd(_mm256_mul_pd(_mm256_xor_pd(at.r, _mm256_set1_pd(-0.0)), mu),
                    _mm256_sqrt_pd(_mm256_max_pd(zero, _mm256_add_pd(rr_mm1, _mm256_set1_pd(rt * rt))))),
      zero);
  const __m256d x_mu = clamp_lanes(_mm256_div_pd(_mm256_sub_pd(d, at.d_min), at.span), 0.0, 1.0);
  const int w = lut.width;
  const __m256d u = _mm256_add_pd(_mm256_set1_pd(0.5 / w),
                                  _mm256_mul_pd(x_mu, _mm256_set1_pd(1.0 - 1.0 / w)));
  const AxisLanes ax = bilinear_axis_lanes(w, lut.channel_count(), u);
  const __m128i o00 = _mm_add_epi32(at.row0, ax.o0), o10 = _mm_add_epi32(at.row0, ax.o1);
  const __m128i o01 = _mm_add_epi32(at.row1, ax.o0), o11 = _mm_add_epi32(at.row1, ax.o1);
  const float* data = lut.data.data();
  const int last = int(lut.data.size()) - lut.channel_count();
  RgbTexelLanes t00 = texel_lanes_loaded(data, o00, last), t10 = texel_lanes_loaded(data, o10, last);
  RgbTexelLanes t01 = texel_lanes_loaded(data, o01, last), t11 = texel_lanes_loaded(data, o11, last);
  for (int c = 0; c < 3; ++c) {  // sample_bilinear_rgb's operations
    const __m256d lo = _mm256_add_pd(t00.c[c], _mm256_mul_pd(ax.f, _mm256_sub_pd(t10.c[c], t00.c[c])));
    const __m256d hi = _mm256_add_pd(t01.c[c], _mm256_mul_pd(ax.f, _mm256_sub_pd(t11.c[c], t01.c[c])));
    const __m256d t = _mm256_add_pd(lo, _mm256_mul_pd(at.fy, _mm256_sub_pd(hi, lo)));
    sum[c] = _mm256_add_pd(sum[c], _mm256_andnot_pd(ground, t));  // Vis = 0: a zero read
  }
}

SKYBAKE_AVX2 void ring_sun_sums_avx2(const Texture& lut, const Atmosphere& atm,
                                     const double* radii, const double* distances,
                                     const double* inverse_radii, size_t n, double height,
                                     const double cosines[4], glm::dvec3* sums) {
  const __m256d h = _mm256_set1_pd(height);
  for (size_t k = 0; k < n; k += 4) {
    // A last group of fewer than four repeats its last sample in the spare lanes.
    const int count = int(std::min<size_t>(4, n - k));
    alignas(32) double r[4], t[4], inv[4];
    for (int j = 0; j < 4; ++j) {
      const size_t i = k + size_t(std::min(j, count - 1));
      r[j] = radii[i];
      t[j] = distances[i];
      inv[j] = inverse_radii[i];
    }
    const RadiusLanes at = radius_lanes(lut, atm, _mm256_load_pd(r));
    const __m256d dist = _mm256_load_pd(t), inverse = _mm256_load_pd(inv);
    __m256d sum[3] = {_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()};
    for (int j = 0; j < 4; ++j) {
      // (height + distance c) / r, then clamp_cosine, as the one-value read.
      const __m256d mu = clamp_lanes(
          _mm256_mul_pd(_mm256_add_pd(h, _mm256_mul_pd(dist, _mm256_set1_pd(cosines[j]))), inverse),
          -1.0, 1.0);
      add_sun_lanes(lut, atm, at, mu, sum);
    }
    alignas(32) double out[3][4];
    for (int c = 0; c < 3; ++c) _mm256_store_pd(out[c], sum[c]);
    for (int j = 0; j < count; ++j) sums[k + size_t(j)] = {out[0][j], out[1][j], out[2][j]};
  }
}
#endif

}  // namespace

bool ring_sun_sums_wide(const Texture& lut, const Atmosphere& atm, const double* radii,
                        const double* distances, const double* inverse_radii, size_t n,
                        double height, const double cosines[4], glm::dvec3* sums) {
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) {
    ring_sun_sums_avx2(lut, atm, radii, distances, inverse_radii, n, height, cosines, sums);
    return true;
  }
#endif
  (void)lut, (void)atm, (void)radii, (void)distances, (void)inverse_radii, (void)n, (void)height,
      (void)cosines, (void)sums;
  return false;
}

}  // namespace skybake

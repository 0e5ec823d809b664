#include "verify/ring_sun_sums.hpp"

#include <algorithm>

#include "atmosphere/kernels/table_read_lanes.hpp"
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

// Where lookup_sun_transmittance(lut, at, rb, mu) reads in each lane, `at`
// the lane's RadiusLanes, mu already clamped: the texels' offsets, the
// weight along the row and Vis (`ground`: all bits set where it is 0).
struct SunTexels {
  __m128i o00, o10, o01, o11;
  __m256d fx, ground;
  bool dark;  // every lane in the planet's shadow
};
SKYBAKE_AVX2 inline SunTexels sun_texels(const Texture& lut, const Atmosphere& atm,
                                         const RadiusLanes& at, __m256d mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const __m256d zero = _mm256_setzero_pd();
  const __m256d rr_mm1 =
      _mm256_mul_pd(_mm256_mul_pd(at.r, at.r), _mm256_sub_pd(_mm256_mul_pd(mu, mu), _mm256_set1_pd(1.0)));
  SunTexels s;
  s.ground = _mm256_and_pd(
      _mm256_cmp_pd(mu, zero, _CMP_LT_OQ),
      _mm256_cmp_pd(_mm256_add_pd(rr_mm1, _mm256_set1_pd(rb * rb)), zero, _CMP_GE_OQ));
  s.dark = _mm256_movemask_pd(s.ground) == 0xF;
  const __m256d d = _mm256_max_pd(  // distance_to_top_boundary
      _mm256_add_pd(_mm256_mul_pd(_mm256_xor_pd(at.r, _mm256_set1_pd(-0.0)), mu),
                    _mm256_sqrt_pd(_mm256_max_pd(zero, _mm256_add_pd(rr_mm1, _mm256_set1_pd(rt * rt))))),
      zero);
  const __m256d x_mu = clamp_lanes(_mm256_div_pd(_mm256_sub_pd(d, at.d_min), at.span), 0.0, 1.0);
  const int w = lut.width;
  const __m256d u = _mm256_add_pd(_mm256_set1_pd(0.5 / w),
                                  _mm256_mul_pd(x_mu, _mm256_set1_pd(1.0 - 1.0 / w)));
  const AxisLanes ax = bilinear_axis_lanes(w, lut.channel_count(), u);
  s.o00 = _mm_add_epi32(at.row0, ax.o0);
  s.o10 = _mm_add_epi32(at.row0, ax.o1);
  s.o01 = _mm_add_epi32(at.row1, ax.o0);
  s.o11 = _mm_add_epi32(at.row1, ax.o1);
  s.fx = ax.f;
  return s;
}

// The read at `s` in each lane (sample_bilinear_rgb's operations), 0 where
// Vis = 0, added to sum[c]. A group wholly in the shadow adds +0 to each
// lane: left out.
SKYBAKE_AVX2 inline void add_sun_texels(const Texture& lut, const SunTexels& s, __m256d fy,
                                        __m256d sum[3]) {
  if (s.dark) return;
  const float* data = lut.data.data();
  const int last = int(lut.data.size()) - lut.channel_count();
  RgbTexelLanes t00 = texel_lanes(data, s.o00, last), t10 = texel_lanes(data, s.o10, last);
  RgbTexelLanes t01 = texel_lanes(data, s.o01, last), t11 = texel_lanes(data, s.o11, last);
  for (int c = 0; c < 3; ++c) {
    const __m256d lo = _mm256_add_pd(t00.c[c], _mm256_mul_pd(s.fx, _mm256_sub_pd(t10.c[c], t00.c[c])));
    const __m256d hi = _mm256_add_pd(t01.c[c], _mm256_mul_pd(s.fx, _mm256_sub_pd(t11.c[c], t01.c[c])));
    const __m256d t = _mm256_add_pd(lo, _mm256_mul_pd(fy, _mm256_sub_pd(hi, lo)));
    sum[c] = _mm256_add_pd(sum[c], _mm256_andnot_pd(s.ground, t));  // Vis = 0: a zero read
  }
}

// A group of four samples (a last group of fewer repeats its last sample in
// the spare lanes): the radius's half of the read and the four azimuths'
// texels.
struct GroupTexels {
  RadiusLanes at;
  SunTexels azimuth[4];
  int count;
};
SKYBAKE_AVX2 inline void group_texels(const Texture& lut, const Atmosphere& atm,
                                      const double* radii, const double* distances,
                                      const double* inverse_radii, size_t k, size_t n,
                                      __m256d height, const double cosines[4], GroupTexels& g) {
  g.count = int(std::min<size_t>(4, n - k));
  const __m256d radius = group_lanes(radii, k, g.count);
  const __m256d dist = group_lanes(distances, k, g.count);
  const __m256d inverse = group_lanes(inverse_radii, k, g.count);
  g.at = radius_lanes(lut, atm, radius);
  for (int j = 0; j < 4; ++j) {
    // (height + distance c) / r, then clamp_cosine, as the one-value read.
    const __m256d mu = clamp_lanes(
        _mm256_mul_pd(_mm256_add_pd(height, _mm256_mul_pd(dist, _mm256_set1_pd(cosines[j]))), inverse),
        -1.0, 1.0);
    g.azimuth[j] = sun_texels(lut, atm, g.at, mu);
  }
}

// The group's reads summed over its azimuths in order, lane by lane, into
// sums[0 .. count).
SKYBAKE_AVX2 inline void group_sums(const Texture& lut, const GroupTexels& g, glm::dvec3* sums) {
  __m256d sum[3] = {_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()};
  for (int j = 0; j < 4; ++j) add_sun_texels(lut, g.azimuth[j], g.at.fy, sum);
  alignas(32) double out[3][4];
  for (int c = 0; c < 3; ++c) _mm256_store_pd(out[c], sum[c]);
  for (int j = 0; j < g.count; ++j) sums[j] = {out[0][j], out[1][j], out[2][j]};
}

// Two groups' coordinates first, then their reads, so that eight
// independent chains of square roots and divisions are in flight at once (a
// read right after its own coordinates waits on the whole chain;
// docs/decisions.md "Error records of the extreme cases, third pass"). The
// same operations per lane: the same bits.
SKYBAKE_AVX2 void ring_sun_sums_avx2(const Texture& lut, const Atmosphere& atm,
                                     const double* radii, const double* distances,
                                     const double* inverse_radii, size_t n, double height,
                                     const double cosines[4], glm::dvec3* sums) {
  const __m256d h = _mm256_set1_pd(height);
  for (size_t k = 0; k < n; k += 8) {
    GroupTexels g[2];
    const int groups = n - k > 4 ? 2 : 1;
    for (int q = 0; q < groups; ++q)
      group_texels(lut, atm, radii, distances, inverse_radii, k + 4 * size_t(q), n, h, cosines,
                   g[q]);
    for (int q = 0; q < groups; ++q) group_sums(lut, g[q], sums + k + 4 * size_t(q));
  }
}
#endif

}  // namespace

bool ring_sun_sums(const Texture& lut, const Atmosphere& atm, const double* radii,
                   const double* distances, const double* inverse_radii, size_t n, double height,
                   const double cosines[4], glm::dvec3* sums) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) {
    ring_sun_sums_avx2(lut, atm, radii, distances, inverse_radii, n, height, cosines, sums);
    return true;
  }
#endif
  (void)lut, (void)atm, (void)radii, (void)distances, (void)inverse_radii, (void)n, (void)height,
      (void)cosines, (void)sums;
  return false;
}

}  // namespace skybake

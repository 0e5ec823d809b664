// The sky LUT reads of the four-wide loops (kernels/skyview_row_luminance.cpp,
// kernels/sunlit_sums.cpp, and the error records' ring_sun_sums.cpp and
// kernels/sun_and_psi_ms_reads.cpp): sample_bilinear_rgb and lookup_sun_transmittance in each of
// four lanes, the same operations on the same operands in the same order as
// the one-value functions, without FMA, so the same bits
// (core/simd_switches.hpp). The clamps are core/wide_intrinsics.hpp's
// clamp_lanes, and std::max(0.0, v) is _mm256_max_pd(v, 0), signed zeros
// included. Texel reads load the same floats (gathers, or one texel's floats
// into one vector), widened to double as the one-value read widens them.
// For the .cpp files of such loops only (core/wide_intrinsics.hpp).
#pragma once

#include "atmosphere/transmittance_lut.hpp"
#include "core/texture_sampling.hpp"
#include "core/wide_intrinsics.hpp"

#if SKYBAKE_HAS_AVX2
namespace skybake {

// Three channels of four lanes.
struct RgbLanes {
  __m256d c[3];
};

// bilinear_axis(u, width, false) in each lane, the texel indices times
// `channels` (offsets into a row): a coordinate that is not finite reads texel 0.
struct AxisLanes {
  __m128i o0, o1;
  __m256d f;
};
SKYBAKE_AVX2 inline AxisLanes bilinear_axis_lanes(int width, int channels, __m256d u) {
  __m256d x = _mm256_sub_pd(_mm256_mul_pd(u, _mm256_set1_pd(double(width))), _mm256_set1_pd(0.5));
  const __m256d finite = _mm256_cmp_pd(_mm256_sub_pd(x, x), _mm256_setzero_pd(), _CMP_EQ_OQ);
  x = clamp_lanes(_mm256_and_pd(x, finite), 0.0, double(width - 1));
  const __m256d x0 = _mm256_floor_pd(x);
  const __m128i i0 = _mm256_cvttpd_epi32(x0);
  const __m128i i1 = _mm_min_epi32(_mm_add_epi32(i0, _mm_set1_epi32(1)), _mm_set1_epi32(width - 1));
  const __m128i ch = _mm_set1_epi32(channels);
  return {_mm_mullo_epi32(i0, ch), _mm_mullo_epi32(i1, ch), _mm256_sub_pd(x, x0)};
}

// One bilinear read of the first three channels, those channels in lanes
// 0-2 (lane 3 is 0): sample_bilinear_rgb's operations on the texels at
// offsets o0, o1 of rows row0, row1 with weights f (along the row) and fy.
// The texels' three floats are loaded masked, never a float past them.
// For reads whose rows differ from one to the next (where
// bilinear_rgb_lanes's gathers would share a row) or whose sum over lanes
// is wanted per channel.
SKYBAKE_AVX2 inline __m256d bilinear_rgb_texels(const float* row0, const float* row1, int o0,
                                                int o1, double f, double fy) {
  const __m128i rgb = _mm_setr_epi32(-1, -1, -1, 0);
  const __m256d t00 = _mm256_cvtps_pd(_mm_maskload_ps(row0 + o0, rgb));
  const __m256d t10 = _mm256_cvtps_pd(_mm_maskload_ps(row0 + o1, rgb));
  const __m256d t01 = _mm256_cvtps_pd(_mm_maskload_ps(row1 + o0, rgb));
  const __m256d t11 = _mm256_cvtps_pd(_mm_maskload_ps(row1 + o1, rgb));
  const __m256d fx = _mm256_set1_pd(f);
  const __m256d lo = _mm256_add_pd(t00, _mm256_mul_pd(fx, _mm256_sub_pd(t10, t00)));
  const __m256d hi = _mm256_add_pd(t01, _mm256_mul_pd(fx, _mm256_sub_pd(t11, t01)));
  return _mm256_add_pd(lo, _mm256_mul_pd(_mm256_set1_pd(fy), _mm256_sub_pd(hi, lo)));
}

// The first three channels of the texels at float offsets `o` of `data`, one
// texel a lane, widened to double: one 128-bit load a texel (its three
// floats and the next), the four transposed; `last` is the offset of the
// table's last texel, loaded masked so that no float past the data is read.
struct RgbTexelLanes {
  __m256d c[3];
};
SKYBAKE_AVX2 inline RgbTexelLanes texel_lanes(const float* data, __m128i o, int last) {
  alignas(16) int off[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(off), o);
  __m128 t[4];
  for (int k = 0; k < 4; ++k)
    t[k] = off[k] < last ? _mm_loadu_ps(data + off[k])
                         : _mm_maskload_ps(data + off[k], _mm_setr_epi32(-1, -1, -1, 0));
  _MM_TRANSPOSE4_PS(t[0], t[1], t[2], t[3]);
  return {{_mm256_cvtps_pd(t[0]), _mm256_cvtps_pd(t[1]), _mm256_cvtps_pd(t[2])}};
}

// sample_bilinear_rgb(tex, row, u) in each lane, tex `width` texels wide
// (bilinear_axis without wrapping: a coordinate that is not finite reads texel 0).
SKYBAKE_AVX2 inline RgbLanes bilinear_rgb_lanes(const BilinearRow& row, int width, __m256d u) {
  const AxisLanes a = bilinear_axis_lanes(width, row.channels, u);
  const __m128i o0 = a.o0, o1 = a.o1;
  const __m256d f = a.f;
  const __m256d fy = _mm256_set1_pd(row.fy);
  RgbLanes out;
  for (int c = 0; c < 3; ++c) {
    const __m256d t00 = _mm256_cvtps_pd(_mm_i32gather_ps(row.row0 + c, o0, 4));
    const __m256d t10 = _mm256_cvtps_pd(_mm_i32gather_ps(row.row0 + c, o1, 4));
    const __m256d t01 = _mm256_cvtps_pd(_mm_i32gather_ps(row.row1 + c, o0, 4));
    const __m256d t11 = _mm256_cvtps_pd(_mm_i32gather_ps(row.row1 + c, o1, 4));
    const __m256d lo = _mm256_add_pd(t00, _mm256_mul_pd(f, _mm256_sub_pd(t10, t00)));
    const __m256d hi = _mm256_add_pd(t01, _mm256_mul_pd(f, _mm256_sub_pd(t11, t01)));
    out.c[c] = _mm256_add_pd(lo, _mm256_mul_pd(fy, _mm256_sub_pd(hi, lo)));
  }
  return out;
}

// lookup_sun_transmittance(lut, at, bottom_m, mu_s)'s texel coordinate u in
// each lane (mu_s already clamped to [-1, 1]) and where Vis = 0 (all bits set
// in `ground`: the sun is below the horizon).
struct SunCoordLanes {
  __m256d u, ground;
};
SKYBAKE_AVX2 inline SunCoordLanes sun_coord_lanes(const TransmittanceAtRadius& at, double bottom_m,
                                                  __m256d mu_s) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d r = _mm256_set1_pd(at.r);
  const __m256d rr_mm1 =
      _mm256_mul_pd(_mm256_mul_pd(r, r), _mm256_sub_pd(_mm256_mul_pd(mu_s, mu_s), one));
  const __m256d ground = _mm256_and_pd(
      _mm256_cmp_pd(mu_s, zero, _CMP_LT_OQ),
      _mm256_cmp_pd(_mm256_add_pd(rr_mm1, _mm256_set1_pd(bottom_m * bottom_m)), zero, _CMP_GE_OQ));
  const __m256d discriminant = _mm256_add_pd(rr_mm1, _mm256_set1_pd(at.top_m * at.top_m));
  const __m256d d = _mm256_max_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(-at.r), mu_s),
                                                _mm256_sqrt_pd(_mm256_max_pd(zero, discriminant))),
                                  zero);
  const __m256d x_mu = clamp_lanes(
      _mm256_div_pd(_mm256_sub_pd(d, _mm256_set1_pd(at.d_min)), _mm256_set1_pd(at.d_max - at.d_min)),
      0.0, 1.0);
  const __m256d u =
      _mm256_add_pd(_mm256_set1_pd(at.u_offset), _mm256_mul_pd(x_mu, _mm256_set1_pd(at.u_scale)));
  return {u, ground};
}

// lookup_sun_transmittance(lut, at, bottom_m, mu_s) in each lane, the table
// `width` texels wide; mu_s already clamped to [-1, 1].
SKYBAKE_AVX2 inline RgbLanes sun_transmittance_lanes(const TransmittanceAtRadius& at, int width,
                                                     double bottom_m, __m256d mu_s) {
  const SunCoordLanes s = sun_coord_lanes(at, bottom_m, mu_s);
  RgbLanes t = bilinear_rgb_lanes(at.row, width, s.u);
  for (__m256d& c : t.c) c = _mm256_andnot_pd(s.ground, c);  // Vis = 0 below the horizon
  return t;
}

}  // namespace skybake
#endif

// skyview_row_luminance: the texels of a sky-view row half, four at a time
// where AVX2 runs (core/wide_vectors.hpp), one at a time otherwise.
//
// The four-wide loop does, per lane, the operations of
// skyview_texel_luminance in the same order on the same operands, without
// FMA, so its values are the same bits (tests/atmosphere/skyview_lut_test.cpp
// bakes with and without it and compares). The clamps follow batch_taps.cpp:
// _mm256_max_pd(lo, v) is std::max(v, lo), _mm256_min_pd(hi, v) is
// std::min(v, hi), std::max(0.0, v) is _mm256_max_pd(v, 0), signed zeros
// included, and std::clamp(v, lo, hi) is their composition for every
// non-NaN v. Texel reads are gathers of the same floats, widened to double
// as the scalar read widens them.
#include <cmath>
#include <vector>

#include "atmosphere/phase.hpp"
#include "atmosphere/skyview_row_march.hpp"
#include "core/wide_intrinsics.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
struct SkyviewLanes {
  __m256d c[3];
};

SKYBAKE_AVX2 inline __m256d skyview_clamp4(__m256d v, double lo, double hi) {
  return _mm256_min_pd(_mm256_set1_pd(hi), _mm256_max_pd(_mm256_set1_pd(lo), v));
}

// sample_bilinear_rgb(tex, row, u) in each lane (bilinear_axis without
// wrapping: a coordinate that is not finite reads texel 0).
SKYBAKE_AVX2 SkyviewLanes skyview_bilinear4(const BilinearRow& row, int width, __m256d u) {
  __m256d x = _mm256_sub_pd(_mm256_mul_pd(u, _mm256_set1_pd(double(width))), _mm256_set1_pd(0.5));
  const __m256d finite = _mm256_cmp_pd(_mm256_sub_pd(x, x), _mm256_setzero_pd(), _CMP_EQ_OQ);
  x = _mm256_and_pd(x, finite);
  x = skyview_clamp4(x, 0.0, double(width - 1));
  const __m256d x0 = _mm256_floor_pd(x);
  const __m256d f = _mm256_sub_pd(x, x0);
  const __m128i i0 = _mm256_cvttpd_epi32(x0);
  const __m128i i1 = _mm_min_epi32(_mm_add_epi32(i0, _mm_set1_epi32(1)), _mm_set1_epi32(width - 1));
  const __m128i ch = _mm_set1_epi32(row.channels);
  const __m128i o0 = _mm_mullo_epi32(i0, ch), o1 = _mm_mullo_epi32(i1, ch);
  const __m256d fy = _mm256_set1_pd(row.fy);
  SkyviewLanes out;
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

// lookup_sun_transmittance(lut, at, bottom_m, mu_s) in each lane; mu_s is
// already clamped to [-1, 1].
SKYBAKE_AVX2 SkyviewLanes skyview_sun_transmittance4(const TransmittanceAtRadius& at, int width,
                                                     double bottom_m, __m256d mu_s) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d r = _mm256_set1_pd(at.r);
  const __m256d rr_mm1 = _mm256_mul_pd(_mm256_mul_pd(r, r), _mm256_sub_pd(_mm256_mul_pd(mu_s, mu_s), one));
  const __m256d ground = _mm256_and_pd(
      _mm256_cmp_pd(mu_s, zero, _CMP_LT_OQ),
      _mm256_cmp_pd(_mm256_add_pd(rr_mm1, _mm256_set1_pd(bottom_m * bottom_m)), zero, _CMP_GE_OQ));
  const __m256d discriminant = _mm256_add_pd(rr_mm1, _mm256_set1_pd(at.top_m * at.top_m));
  const __m256d d = _mm256_max_pd(
      _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(-at.r), mu_s),
                    _mm256_sqrt_pd(_mm256_max_pd(zero, discriminant))),
      zero);
  const __m256d x_mu = skyview_clamp4(
      _mm256_div_pd(_mm256_sub_pd(d, _mm256_set1_pd(at.d_min)), _mm256_set1_pd(at.d_max - at.d_min)),
      0.0, 1.0);
  const __m256d u =
      _mm256_add_pd(_mm256_set1_pd(at.u_offset), _mm256_mul_pd(x_mu, _mm256_set1_pd(at.u_scale)));
  SkyviewLanes t = skyview_bilinear4(at.row, width, u);
  for (__m256d& c : t.c) c = _mm256_andnot_pd(ground, c);  // Vis = 0 below the horizon
  return t;
}

// skyview_texel_luminance for texels k .. k + 3 (linear sun mapping only).
SKYBAKE_AVX2 void skyview_four_texels(const SkyviewRowMarch& row, const Atmosphere& atm,
                                      const Texture& transmittance_lut,
                                      const Texture& multiscattering_lut, const double* cos_phi,
                                      const double* phase, double cos_theta_s,
                                      double sin_theta_s, glm::dvec3* out) {
  const size_t nc = row.components.size();
  const __m256d zero = _mm256_setzero_pd();
  // phase[(c * 3 + channel) * 4 + lane]: sigma_s p(nu) of component c.
  const __m256d across_scale = _mm256_mul_pd(_mm256_loadu_pd(cos_phi), _mm256_set1_pd(sin_theta_s));
  __m256d lum[3] = {zero, zero, zero};
  const double* density = row.densities.data();
  for (const SkyviewRowSegment& seg : row.segments) {
    __m256d ssp[3] = {zero, zero, zero};
    for (size_t c = 0; c < nc; ++c)
      for (int ch = 0; ch < 3; ++ch)
        ssp[ch] = _mm256_add_pd(ssp[ch], _mm256_mul_pd(_mm256_set1_pd(density[c]),
                                                       _mm256_loadu_pd(phase + (c * 3 + ch) * 4)));
    density += nc;
    const __m256d mu_s = skyview_clamp4(
        _mm256_add_pd(_mm256_set1_pd(seg.along * cos_theta_s),
                      _mm256_mul_pd(_mm256_set1_pd(seg.across), across_scale)),
        -1.0, 1.0);
    const SkyviewLanes t_sun = skyview_sun_transmittance4(seg.transmittance, transmittance_lut.width,
                                                          atm.bottom_radius_m, mu_s);
    const MultiscatteringAtRadius& ms_at = seg.multiscattering;
    const __m256d x = _mm256_add_pd(_mm256_set1_pd(0.5), _mm256_mul_pd(_mm256_set1_pd(0.5), mu_s));
    const SkyviewLanes ms = skyview_bilinear4(
        ms_at.row, multiscattering_lut.width,
        _mm256_add_pd(_mm256_set1_pd(ms_at.u_offset), _mm256_mul_pd(x, _mm256_set1_pd(ms_at.u_scale))));
    for (int ch = 0; ch < 3; ++ch) {  // eq. 11
      const __m256d source = _mm256_add_pd(_mm256_mul_pd(t_sun.c[ch], ssp[ch]),
                                           _mm256_mul_pd(ms.c[ch], _mm256_set1_pd(seg.sigma_s[ch])));
      lum[ch] = _mm256_add_pd(lum[ch], _mm256_mul_pd(_mm256_set1_pd(seg.view_weight[ch]), source));
    }
  }
  alignas(32) double lanes[3][4];
  for (int ch = 0; ch < 3; ++ch) _mm256_store_pd(lanes[ch], lum[ch]);
  for (int k = 0; k < 4; ++k) out[k] = glm::dvec3(lanes[0][k], lanes[1][k], lanes[2][k]);
}

// The texels the four-wide loop does: all but the last n % 4; none where the
// sun's lookup uses the terminator mapping (an arctangent per read).
SKYBAKE_AVX2 int skyview_row_avx2(const SkyviewRowMarch& row, const Atmosphere& atm,
                                  const Texture& transmittance_lut,
                                  const Texture& multiscattering_lut, const double* cos_phi,
                                  const double* nu, int n, double cos_theta_s, double sin_theta_s,
                                  glm::dvec3* out) {
  if (row.segments.empty() ||
      row.segments.front().multiscattering.mapping.sun != SunMapping::linear)
    return 0;
  const size_t nc = row.components.size();
  std::vector<double> phase(nc * 3 * 4);
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    for (size_t c = 0; c < nc; ++c) {
      const MediumComponent& m = *row.components[c];
      for (int lane = 0; lane < 4; ++lane) {
        const glm::dvec3 sp = m.scattering_per_m * phase_function(m.phase, m.g, nu[k + lane]);
        for (int ch = 0; ch < 3; ++ch) phase[(c * 3 + ch) * 4 + lane] = sp[ch];
      }
    }
    skyview_four_texels(row, atm, transmittance_lut, multiscattering_lut, cos_phi + k,
                        phase.data(), cos_theta_s, sin_theta_s, out + k);
  }
  return k;
}
#endif

}  // namespace

void skyview_row_luminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                           const Texture& transmittance_lut, const Texture& multiscattering_lut,
                           const double* cos_phi, const double* nu, int n, double cos_theta_s,
                           double sin_theta_s, glm::dvec3* out) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (wide_vectors())
    first = skyview_row_avx2(row, atm, transmittance_lut, multiscattering_lut, cos_phi, nu, n,
                             cos_theta_s, sin_theta_s, out);
#endif
  std::vector<glm::dvec3> scratch;
  for (int k = first; k < n; ++k)
    out[k] = skyview_texel_luminance(row, atm, transmittance_lut, multiscattering_lut, cos_phi[k],
                                     cos_theta_s, sin_theta_s, nu[k], scratch);
}

}  // namespace skybake

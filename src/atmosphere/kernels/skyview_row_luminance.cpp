// skyview_row_luminance: the texels of a sky-view row half, four at a time
// where AVX2 runs (core/simd_switches.hpp), one at a time otherwise.
//
// The four-wide loop does, per lane, the operations of
// skyview_texel_luminance in the same order on the same operands, with the
// reads of atmosphere/kernels/table_read_lanes.hpp, so its values are the same bits
// (tests/atmosphere/avx2_bakes_test.cpp bakes with and without it and
// compares).
#include "atmosphere/kernels/skyview_row_luminance.hpp"

#include <cmath>
#include <vector>

#include "atmosphere/kernels/table_read_lanes.hpp"
#include "atmosphere/phase.hpp"

namespace skybake {

namespace {

#if SKYBAKE_HAS_AVX2
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
    const __m256d mu_s = clamp_lanes(
        _mm256_add_pd(_mm256_set1_pd(seg.along * cos_theta_s),
                      _mm256_mul_pd(_mm256_set1_pd(seg.across), across_scale)),
        -1.0, 1.0);
    const RgbLanes t_sun = sun_transmittance_lanes(seg.transmittance, transmittance_lut.width,
                                                          atm.bottom_radius_m, mu_s);
    const MultiscatteringAtRadius& ms_at = seg.multiscattering;
    const __m256d x = _mm256_add_pd(_mm256_set1_pd(0.5), _mm256_mul_pd(_mm256_set1_pd(0.5), mu_s));
    const RgbLanes ms = bilinear_rgb_lanes(
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
  if (avx2_enabled())
    first = skyview_row_avx2(row, atm, transmittance_lut, multiscattering_lut, cos_phi, nu, n,
                             cos_theta_s, sin_theta_s, out);
#endif
  std::vector<glm::dvec3> scratch;
  for (int k = first; k < n; ++k)
    out[k] = skyview_texel_luminance(row, atm, transmittance_lut, multiscattering_lut, cos_phi[k],
                                     cos_theta_s, sin_theta_s, nu[k], scratch);
}

}  // namespace skybake

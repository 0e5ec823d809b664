#include "atmosphere/kernels/sun_and_psi_ms_reads.hpp"

#include <algorithm>

#include "atmosphere/kernels/table_read_lanes.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

#if SKYBAKE_HAS_AVX2
// Where a group's read of a table falls: texel coordinates u, v in each lane,
// and the lanes that read 0 (all bits set in `zero`; `dark`: every lane).
struct ReadCoords {
  __m256d u, v, zero;
  bool dark;
};

// Lane k's bilinear read of `tex` at texel coordinates (at.u, at.v), its
// three channels in out[k]'s, for the first `count` lanes; lanes whose
// `zero` bits are set read 0 (the one-value read's early return of +0),
// without a load when all are.
SKYBAKE_AVX2 void read_lanes(const Texture& tex, const ReadCoords& at, int count,
                             glm::dvec3* out) {
  if (at.dark) {
    for (int k = 0; k < count; ++k) out[k] = glm::dvec3(0.0);
    return;
  }
  const __m256d u = at.u, v = at.v, zero = at.zero;
  const int channels = tex.channel_count();
  const AxisLanes ax = bilinear_axis_lanes(tex.width, channels, u);
  const AxisLanes ay = bilinear_axis_lanes(tex.height, tex.width * channels, v);
  alignas(32) double fx[4], fy[4], keep[4], rgb[4];
  alignas(16) int o0[4], o1[4], row0[4], row1[4];
  _mm256_store_pd(fx, ax.f);
  _mm256_store_pd(fy, ay.f);
  _mm256_store_pd(keep, _mm256_castsi256_pd(
                            _mm256_xor_si256(_mm256_castpd_si256(zero), _mm256_set1_epi64x(-1))));
  _mm_store_si128(reinterpret_cast<__m128i*>(o0), ax.o0);
  _mm_store_si128(reinterpret_cast<__m128i*>(o1), ax.o1);
  _mm_store_si128(reinterpret_cast<__m128i*>(row0), ay.o0);
  _mm_store_si128(reinterpret_cast<__m128i*>(row1), ay.o1);
  const float* data = tex.data.data();
  for (int k = 0; k < count; ++k) {
    const __m256d t =
        bilinear_rgb_texels(data + row0[k], data + row1[k], o0[k], o1[k], fx[k], fy[k]);
    _mm256_store_pd(rgb, _mm256_and_pd(t, _mm256_set1_pd(keep[k])));
    out[k] = glm::dvec3(rgb[0], rgb[1], rgb[2]);
  }
}

// texel_coord_from_unit(x, n) in each lane.
SKYBAKE_AVX2 inline __m256d texel_lanes(__m256d x, int n) {
  return _mm256_add_pd(_mm256_set1_pd(0.5 / n), _mm256_mul_pd(x, _mm256_set1_pd(1.0 - 1.0 / n)));
}

// lookup_sun_transmittance(lut, atm, r, mu_s)'s coordinates in each lane: the
// clamps, Vis, then transmittance_uv_from_r_mu's operations.
SKYBAKE_AVX2 inline ReadCoords sun_coords(const Atmosphere& atm, const Texture& lut, __m256d r,
                                          __m256d mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double horizon = safe_sqrt((rt - rb) * (rt + rb));  // horizon_distance
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  r = clamp_lanes(r, rb, rt);
  mu = clamp_lanes(mu, -1.0, 1.0);
  const __m256d rr_mm1 = _mm256_mul_pd(_mm256_mul_pd(r, r), _mm256_sub_pd(_mm256_mul_pd(mu, mu), one));
  const __m256d ground = _mm256_and_pd(
      _mm256_cmp_pd(mu, zero, _CMP_LT_OQ),
      _mm256_cmp_pd(_mm256_add_pd(rr_mm1, _mm256_set1_pd(rb * rb)), zero, _CMP_GE_OQ));
  const __m256d rho = _mm256_sqrt_pd(_mm256_max_pd(
      zero, _mm256_mul_pd(_mm256_sub_pd(r, _mm256_set1_pd(rb)), _mm256_add_pd(r, _mm256_set1_pd(rb)))));
  const __m256d d = _mm256_max_pd(  // distance_to_top_boundary: max(0, -r mu + safe_sqrt(...))
      _mm256_add_pd(_mm256_mul_pd(_mm256_xor_pd(r, _mm256_set1_pd(-0.0)), mu),
                    _mm256_sqrt_pd(_mm256_max_pd(zero, _mm256_add_pd(rr_mm1, _mm256_set1_pd(rt * rt))))),
      zero);
  const __m256d d_min = _mm256_sub_pd(_mm256_set1_pd(rt), r);
  const __m256d d_max = _mm256_add_pd(rho, _mm256_set1_pd(horizon));
  const __m256d x_mu =
      clamp_lanes(_mm256_div_pd(_mm256_sub_pd(d, d_min), _mm256_sub_pd(d_max, d_min)), 0.0, 1.0);
  const __m256d x_r = _mm256_div_pd(rho, _mm256_set1_pd(horizon));
  return {texel_lanes(x_mu, lut.width), texel_lanes(x_r, lut.height), ground,
          _mm256_movemask_pd(ground) == 0xF};
}

// lookup_multiscattering(lut, m, atm, r, mu_s)'s coordinates in each lane:
// multiscattering_uv_from_r_mu_s's operations; the terminator mapping's
// x_mu_s is unit_from_sun_cosine's own, lane by lane.
SKYBAKE_AVX2 inline ReadCoords multiscattering_coords(const Atmosphere& atm, const Texture& lut,
                                                      const MultiscatteringMapping& m, __m256d r,
                                                      __m256d mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  r = clamp_lanes(r, rb, rt);
  __m256d x_mu;
  if (m.sun == SunMapping::linear) {
    x_mu = _mm256_add_pd(_mm256_set1_pd(0.5),
                         _mm256_mul_pd(_mm256_set1_pd(0.5), clamp_lanes(mu, -1.0, 1.0)));
  } else {
    alignas(32) double rl[4], ml[4], xl[4];
    _mm256_store_pd(rl, r);
    _mm256_store_pd(ml, mu);
    for (int k = 0; k < 4; ++k) xl[k] = unit_from_sun_cosine(m, atm, rl[k], ml[k]);
    x_mu = _mm256_load_pd(xl);
  }
  __m256d x_h = _mm256_div_pd(_mm256_sub_pd(r, _mm256_set1_pd(rb)), _mm256_set1_pd(rt - rb));
  if (m.altitude == AltitudeMapping::quadratic) x_h = _mm256_sqrt_pd(x_h);
  return {texel_lanes(x_mu, lut.width), texel_lanes(x_h, lut.height), _mm256_setzero_pd(), false};
}

SKYBAKE_AVX2 void sky_reads_avx2(const Atmosphere& atm, const Texture& transmittance_lut,
                                 const Texture* multiscattering_lut,
                                 const MultiscatteringMapping& mapping, const double* r,
                                 const double* mu_s, size_t n, glm::dvec3* sun, glm::dvec3* ms) {
  // Two groups' coordinates first, then their reads: the chains of square
  // roots and divisions of both tables and both groups in flight at once.
  for (size_t k = 0; k < n; k += 8) {
    const int groups = n - k > 4 ? 2 : 1;
    int count[2];
    ReadCoords sun_at[2], ms_at[2];
    for (int q = 0; q < groups; ++q) {
      const size_t first = k + 4 * size_t(q);
      count[q] = int(std::min<size_t>(4, n - first));
      const __m256d rv = group_lanes(r, first, count[q]), mv = group_lanes(mu_s, first, count[q]);
      sun_at[q] = sun_coords(atm, transmittance_lut, rv, mv);
      if (multiscattering_lut)
        ms_at[q] = multiscattering_coords(atm, *multiscattering_lut, mapping, rv, mv);
    }
    for (int q = 0; q < groups; ++q) {
      const size_t first = k + 4 * size_t(q);
      read_lanes(transmittance_lut, sun_at[q], count[q], sun + first);
      if (multiscattering_lut) read_lanes(*multiscattering_lut, ms_at[q], count[q], ms + first);
    }
  }
  // GCC leaves out the vzeroupper after calls that pass 256-bit values: the
  // SSE2 code that follows (the march, the next bake) would then run with the
  // upper halves dirty, measured 20% slower on the aerial table's bake.
  _mm256_zeroupper();
}
#endif

}  // namespace

void read_sun_and_psi_ms(const Atmosphere& atm, const Texture& transmittance_lut,
               const Texture* multiscattering_lut, const MultiscatteringMapping& mapping,
               const double* r, const double* mu_s, size_t n, glm::dvec3* sun, glm::dvec3* ms) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) {
    sky_reads_avx2(atm, transmittance_lut, multiscattering_lut, mapping, r, mu_s, n, sun, ms);
    return;
  }
#endif
  for (size_t k = 0; k < n; ++k) {
    sun[k] = lookup_sun_transmittance(transmittance_lut, atm, r[k], mu_s[k]);
    if (multiscattering_lut)
      ms[k] = lookup_multiscattering(*multiscattering_lut, mapping, atm, r[k], mu_s[k]);
  }
}

}  // namespace skybake

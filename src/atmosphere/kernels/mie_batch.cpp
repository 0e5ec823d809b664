// The density's Mie loop in SSE2, AVX2 and AVX-512 (twins, the same bits:
// core/simd_switches.hpp) and its plain C++ fallback. See the header.
#include "atmosphere/kernels/mie_batch.hpp"

#include <algorithm>
#include <cmath>

#include "core/wide_intrinsics.hpp"

namespace skybake {

namespace {

// The arguments of one sums() call: the view, the kernel and the arrays.
struct MieLoop {
  float vx, vy, vz, a, b, cs;  // cs: 1 for Cornette-Shanks, 0 for Henyey-Greenstein
  const float *x, *y, *z, *blocks;
  size_t n;
  // Channel c of the pairs from j (MieBatch::field).
  const float* channel(int c, size_t j) const { return blocks + MieBatch::field(c, j); }
};

// lanes[c][l]: channel c (R, G, B, weight), lane l.
using MieLanes = float[4][MieBatch::kLanes];

#if defined(__SSE2__)
// Four pairs from j into four lanes (acc: R, G, B, weight).
inline void mie_step_sse2(const MieLoop& q, size_t j, __m128 acc[4]) {
  const __m128 one = _mm_set1_ps(1.0f), zero = _mm_setzero_ps();
  const __m128 a = _mm_set1_ps(q.a), b = _mm_set1_ps(q.b), cs = _mm_set1_ps(q.cs);
  const __m128 in_plane = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(q.vx), _mm_loadu_ps(q.x + j)),
                                     _mm_mul_ps(_mm_set1_ps(q.vz), _mm_loadu_ps(q.z + j)));
  const __m128 across = _mm_mul_ps(_mm_set1_ps(q.vy), _mm_loadu_ps(q.y + j));
  const __m128 cp = _mm_add_ps(in_plane, across), cm = _mm_sub_ps(in_plane, across);
  const __m128 wp = _mm_add_ps(a, _mm_mul_ps(b, _mm_max_ps(_mm_sub_ps(one, cp), zero)));
  const __m128 wm = _mm_add_ps(a, _mm_mul_ps(b, _mm_max_ps(_mm_sub_ps(one, cm), zero)));
  const __m128 qp = _mm_mul_ps(wp, _mm_sqrt_ps(wp)), qm = _mm_mul_ps(wm, _mm_sqrt_ps(wm));
  const __m128 np = _mm_add_ps(one, _mm_mul_ps(cs, _mm_mul_ps(cp, cp)));
  const __m128 nm = _mm_add_ps(one, _mm_mul_ps(cs, _mm_mul_ps(cm, cm)));
  const __m128 p =
      _mm_div_ps(_mm_add_ps(_mm_mul_ps(np, qm), _mm_mul_ps(nm, qp)), _mm_mul_ps(qp, qm));
  for (int c = 0; c < 4; ++c) acc[c] = _mm_add_ps(acc[c], _mm_mul_ps(p, _mm_loadu_ps(q.channel(c, j))));
}

// Lanes 0-3 take the first four pairs of every eight, lanes 4-7 the others.
void mie_sums_sse2(const MieLoop& q, MieLanes lanes) {
  __m128 low[4], high[4];
  for (int c = 0; c < 4; ++c) low[c] = high[c] = _mm_setzero_ps();
  for (size_t j = 0; j < q.n; j += 8) {
    mie_step_sse2(q, j, low);
    mie_step_sse2(q, j + 4, high);
  }
  for (int c = 0; c < 4; ++c) {
    _mm_storeu_ps(lanes[c], low[c]);
    _mm_storeu_ps(lanes[c] + 4, high[c]);
  }
}
#endif

#if SKYBAKE_HAS_AVX2
// MieBatch::sums' sum of the lanes, ((s0 + s1) + (s2 + s3)) + ((s4 + s5) +
// (s6 + s7)) in double, for the four sums at once: the same additions of
// the same operands.
// (c0 + c1) + (c2 + c3) of four lanes of each sum c = r, g, b, w.
SKYBAKE_AVX2 inline __m256d half_sums(__m128 r, __m128 g, __m128 b, __m128 w) {
  const __m256d rg = _mm256_hadd_pd(_mm256_cvtps_pd(r), _mm256_cvtps_pd(g));  // r01 g01 r23 g23
  const __m256d bw = _mm256_hadd_pd(_mm256_cvtps_pd(b), _mm256_cvtps_pd(w));
  return _mm256_add_pd(_mm256_permute2f128_pd(rg, bw, 0x20), _mm256_permute2f128_pd(rg, bw, 0x31));
}
SKYBAKE_AVX2 inline void add_lanes_avx2(__m256 sr, __m256 sg, __m256 sb, __m256 sw, double out[4]) {
  const __m256d low = half_sums(_mm256_castps256_ps128(sr), _mm256_castps256_ps128(sg),
                                _mm256_castps256_ps128(sb), _mm256_castps256_ps128(sw));
  const __m256d high = half_sums(_mm256_extractf128_ps(sr, 1), _mm256_extractf128_ps(sg, 1),
                                 _mm256_extractf128_ps(sb, 1), _mm256_extractf128_ps(sw, 1));
  _mm256_storeu_pd(out, _mm256_add_pd(low, high));
}

// mie_sums_sse2 with its two halves in one register, and the lanes summed.
SKYBAKE_AVX2 void mie_sums_avx2(const MieLoop& q, double out[4]) {
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const __m256 a = _mm256_set1_ps(q.a), b = _mm256_set1_ps(q.b), cs = _mm256_set1_ps(q.cs);
  const __m256 vx = _mm256_set1_ps(q.vx), vy = _mm256_set1_ps(q.vy), vz = _mm256_set1_ps(q.vz);
  __m256 sr = _mm256_setzero_ps(), sg = sr, sb = sr, sw = sr;
  for (size_t j = 0; j < q.n; j += 8) {
    const __m256 in_plane = _mm256_add_ps(_mm256_mul_ps(vx, _mm256_loadu_ps(q.x + j)),
                                          _mm256_mul_ps(vz, _mm256_loadu_ps(q.z + j)));
    const __m256 across = _mm256_mul_ps(vy, _mm256_loadu_ps(q.y + j));
    const __m256 cp = _mm256_add_ps(in_plane, across), cm = _mm256_sub_ps(in_plane, across);
    const __m256 wp =
        _mm256_add_ps(a, _mm256_mul_ps(b, _mm256_max_ps(_mm256_sub_ps(one, cp), zero)));
    const __m256 wm =
        _mm256_add_ps(a, _mm256_mul_ps(b, _mm256_max_ps(_mm256_sub_ps(one, cm), zero)));
    const __m256 qp = _mm256_mul_ps(wp, _mm256_sqrt_ps(wp));
    const __m256 qm = _mm256_mul_ps(wm, _mm256_sqrt_ps(wm));
    const __m256 np = _mm256_add_ps(one, _mm256_mul_ps(cs, _mm256_mul_ps(cp, cp)));
    const __m256 nm = _mm256_add_ps(one, _mm256_mul_ps(cs, _mm256_mul_ps(cm, cm)));
    const __m256 p = _mm256_div_ps(_mm256_add_ps(_mm256_mul_ps(np, qm), _mm256_mul_ps(nm, qp)),
                                   _mm256_mul_ps(qp, qm));
    sr = _mm256_add_ps(sr, _mm256_mul_ps(p, _mm256_loadu_ps(q.channel(0, j))));
    sg = _mm256_add_ps(sg, _mm256_mul_ps(p, _mm256_loadu_ps(q.channel(1, j))));
    sb = _mm256_add_ps(sb, _mm256_mul_ps(p, _mm256_loadu_ps(q.channel(2, j))));
    sw = _mm256_add_ps(sw, _mm256_mul_ps(p, _mm256_loadu_ps(q.channel(3, j))));
  }
  add_lanes_avx2(sr, sg, sb, sw, out);
}
#endif

#if defined(SKYBAKE_AVX512)
// mie_sums_avx2 with the kernel of sixteen pairs per step (the square roots
// and the division at twice the lanes), each half added into the eight
// lanes as mie_sums_avx2 adds the step of its pairs: the same sums in the
// same order. A last group of eight pairs (n is a multiple of 8) is loaded
// under a mask and its upper half not added.
SKYBAKE_AVX512_WARNINGS_OFF
SKYBAKE_AVX512 void mie_sums_avx512(const MieLoop& q, double out[4]) {
  const __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
  const __m512 a = _mm512_set1_ps(q.a), b = _mm512_set1_ps(q.b), cs = _mm512_set1_ps(q.cs);
  const __m512 vx = _mm512_set1_ps(q.vx), vy = _mm512_set1_ps(q.vy), vz = _mm512_set1_ps(q.vz);
  // Lanes 0-7 of rg are mie_sums_avx2's sr, 8-15 its sg; bw: sb and sw.
  __m512 rg = _mm512_setzero_ps(), bw = rg;
  for (size_t j = 0; j < q.n; j += 16) {
    // Past the last pair (n a multiple of 8, not of 16): lanes of weight 0.
    const __mmask16 in = j + 16 <= q.n ? __mmask16(0xffff) : __mmask16(0x00ff);
    const __m512 in_plane = _mm512_add_ps(_mm512_mul_ps(vx, _mm512_maskz_loadu_ps(in, q.x + j)),
                                          _mm512_mul_ps(vz, _mm512_maskz_loadu_ps(in, q.z + j)));
    const __m512 across = _mm512_mul_ps(vy, _mm512_maskz_loadu_ps(in, q.y + j));
    const __m512 cp = _mm512_add_ps(in_plane, across), cm = _mm512_sub_ps(in_plane, across);
    const __m512 wp =
        _mm512_add_ps(a, _mm512_mul_ps(b, _mm512_max_ps(_mm512_sub_ps(one, cp), zero)));
    const __m512 wm =
        _mm512_add_ps(a, _mm512_mul_ps(b, _mm512_max_ps(_mm512_sub_ps(one, cm), zero)));
    const __m512 qp = _mm512_mul_ps(wp, _mm512_sqrt_ps(wp));
    const __m512 qm = _mm512_mul_ps(wm, _mm512_sqrt_ps(wm));
    const __m512 np = _mm512_add_ps(one, _mm512_mul_ps(cs, _mm512_mul_ps(cp, cp)));
    const __m512 nm = _mm512_add_ps(one, _mm512_mul_ps(cs, _mm512_mul_ps(cm, cm)));
    const __m512 p = _mm512_div_ps(_mm512_add_ps(_mm512_mul_ps(np, qm), _mm512_mul_ps(nm, qp)),
                                   _mm512_mul_ps(qp, qm));
    // Each block of 8 pairs with its kernel in both halves (p0 p0, p1 p1).
    const __m512 halves[2] = {_mm512_shuffle_f32x4(p, p, 0x44), _mm512_shuffle_f32x4(p, p, 0xee)};
    for (size_t h = 0; h < 2 && j + 8 * h < q.n; ++h) {
      const size_t k = j + 8 * h;
      rg = _mm512_add_ps(rg, _mm512_mul_ps(halves[h], _mm512_loadu_ps(q.channel(0, k))));
      bw = _mm512_add_ps(bw, _mm512_mul_ps(halves[h], _mm512_loadu_ps(q.channel(2, k))));
    }
  }
  // A call (other options), once per view.
  add_lanes_avx2(_mm512_castps512_ps256(rg), _mm512_extractf32x8_ps(rg, 1),
                 _mm512_castps512_ps256(bw), _mm512_extractf32x8_ps(bw, 1), out);
}
SKYBAKE_AVX512_WARNINGS_ON
#endif

// The same operations one lane at a time, for CPUs without SSE2.
[[maybe_unused]] void mie_sums_plain(const MieLoop& q, MieLanes lanes) {
  for (int c = 0; c < 4; ++c)
    for (size_t l = 0; l < MieBatch::kLanes; ++l) lanes[c][l] = 0.0f;
  for (size_t j = 0; j < q.n; ++j) {
    const size_t l = j % MieBatch::kLanes;
    const float in_plane = q.vx * q.x[j] + q.vz * q.z[j];
    const float across = q.vy * q.y[j];
    const float cp = in_plane + across, cm = in_plane - across;
    const float wp = q.a + q.b * std::max(1.0f - cp, 0.0f);
    const float wm = q.a + q.b * std::max(1.0f - cm, 0.0f);
    const float qp = wp * std::sqrt(wp), qm = wm * std::sqrt(wm);
    const float p = ((1.0f + q.cs * (cp * cp)) * qm + (1.0f + q.cs * (cm * cm)) * qp) / (qp * qm);
    for (int c = 0; c < 4; ++c) lanes[c][l] += p * *q.channel(c, j);
  }
}

}  // namespace

MieBatch::MieBatch(const SphereGrid& grid) {
  const int half = grid.azimuths / 2;
  for (int l = 0; l < grid.bands; ++l)
    for (int m = 0; m < half; ++m) first.push_back(size_t(l) * grid.azimuths + m);
  n = (first.size() + kLanes - 1) / kLanes * kLanes;
  for (auto* v : {&x, &y, &z}) v->assign(n, 0.0f);
  blocks.assign(4 * n, 0.0f);
  for (size_t k = 0; k < first.size(); ++k) {
    const glm::dvec3& w = grid.directions[first[k]];
    x[k] = float(w.x);
    y[k] = float(w.y);
    z[k] = float(w.z);
    blocks[field(3, k)] = float(grid.solid_angle[first[k]]);
  }
  grid_azimuths = grid.azimuths;
}

void MieBatch::set_field(const std::vector<glm::dvec3>& L) {
  for (size_t k = 0; k < first.size(); ++k) {
    const size_t j = first[k], mirror = j + grid_azimuths - 1 - 2 * (j % grid_azimuths);
    const glm::dvec3 mean = 0.5 * (L[j] + L[mirror]);
    const float dw = blocks[field(3, k)];
    for (int c = 0; c < 3; ++c) blocks[field(c, k)] = float(mean[c] * dw);
  }
}

void MieBatch::sums(const MieKernel& k, const glm::dvec3& v, double out[4]) const {
  const MieLoop q{float(v.x), float(v.y), float(v.z), float(k.a),    float(k.b),
                  k.cornette_shanks ? 1.0f : 0.0f, x.data(), y.data(), z.data(), blocks.data(), n};
#if defined(SKYBAKE_AVX512)
  if (avx512_enabled()) {
    mie_sums_avx512(q, out);
    return;
  }
#endif
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) {
    mie_sums_avx2(q, out);
    return;
  }
#endif
  MieLanes lanes;
#if defined(__SSE2__)
  mie_sums_sse2(q, lanes);
#else
  mie_sums_plain(q, lanes);
#endif
  for (int c = 0; c < 4; ++c) {
    const float* s = lanes[c];
    out[c] = ((double(s[0]) + s[1]) + (double(s[2]) + s[3])) +
             ((double(s[4]) + s[5]) + (double(s[6]) + s[7]));
  }
}

}  // namespace skybake

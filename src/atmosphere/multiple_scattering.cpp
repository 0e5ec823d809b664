// DeltaS_k of the 4D table: J_k integrated along view rays, the direct
// quadrature and the fast path that shares a row's nodes and (r, mu) taps.
// See scattering_orders.hpp for the equations.
#include "atmosphere/multiple_scattering.hpp"

#include <algorithm>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/wide_vectors.hpp"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif
#if SKYBAKE_HAS_AVX2
#include <immintrin.h>
#endif

#include "atmosphere/geometry.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "core/math.hpp"

namespace skybake {

Texture density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                               const Texture& density) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  std::vector<glm::dvec3> sigma_s(shape.r_size);
  for (int z = 0; z < shape.r_size; ++z)
    sigma_s[z] = sample_medium(atm, texels.r[z] - atm.bottom_radius_m).scattering;
  Texture out = density;
  // Each r slice on its own (it reads others, writes only itself).
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int c = 0; c < 3; ++c) {
      // Where sigma_s = 0 (a layer that ends at the top texel, r = Rt
      // exactly), J / sigma_s is undefined: take the nearest r texel's.
      int from = z;
      for (int k = 1; sigma_s[from][c] == 0.0 && k < shape.r_size; ++k)
        for (int candidate : {z - k, z + k})
          if (candidate >= 0 && candidate < shape.r_size && sigma_s[candidate][c] > 0.0 &&
              sigma_s[from][c] == 0.0)
            from = candidate;
      for (int y = 0; y < density.height; ++y)
        for (int x = 0; x < density.width; ++x)
          out.texel(x, y, z)[c] = sigma_s[from][c] > 0.0
                                      ? float(density.texel(x, y, from)[c] / sigma_s[from][c])
                                      : 0.0f;
    }
  });
  return out;
}

glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                       const Texture& density_per_sigma_s, double r, double mu,
                                       double mu_s, double nu, bool ray_hits_ground, int nodes) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double d = distance_to_nearest_boundary(rb, rt, r, mu, ray_hits_ground);
  const Texture& radiance = density_per_sigma_s;
  RayTransfer transfer;
  ray_transfer(atm, r, mu, d, nodes, transfer);
  glm::dvec3 sum(0.0);
  for (const TransferNode& q : transfer.nodes) {
    const double mu_i = mu_after(r, mu, q.s, q.r);
    const double mu_s_i = clamp_cosine((r * mu_s + q.s * nu) / q.r);
    const glm::dvec3 sigma_s = sample_medium(atm, q.r - rb).scattering;
    sum += q.weight * sigma_s *
           lookup_scattering_rgb(radiance, shape, atm, q.r, mu_i, mu_s_i, nu, ray_hits_ground);
  }
  return sum;
}

namespace {

// Four floats: R G B and a zero pad, so a texel is one SSE register.
struct alignas(16) Rgb4 {
  float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

#if SKYBAKE_HAS_AVX2
// blend_rows two texels at a time (the same operations per lane); returns
// how many texels it did.
SKYBAKE_AVX2 int blend_rows_avx2(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  const __m256 w0 = _mm256_set1_ps(w[0]), w1 = _mm256_set1_ps(w[1]), w2 = _mm256_set1_ps(w[2]),
               w3 = _mm256_set1_ps(w[3]);
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m256 a = _mm256_mul_ps(w0, _mm256_loadu_ps(rows[0][i].v));
    const __m256 b = _mm256_mul_ps(w1, _mm256_loadu_ps(rows[1][i].v));
    const __m256 c = _mm256_mul_ps(w2, _mm256_loadu_ps(rows[2][i].v));
    const __m256 d = _mm256_mul_ps(w3, _mm256_loadu_ps(rows[3][i].v));
    _mm256_storeu_ps(out[i].v, _mm256_add_ps(_mm256_add_ps(a, b), _mm256_add_ps(c, d)));
  }
  return i;
}
#endif

// out = w0 a + w1 b + w2 c + w3 d over n texels.
void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  int first = 0;
#if SKYBAKE_HAS_AVX2
  if (wide_vectors()) first = blend_rows_avx2(rows, w, n, out);
#endif
#if defined(__SSE2__)
  const __m128 w0 = _mm_set1_ps(w[0]), w1 = _mm_set1_ps(w[1]), w2 = _mm_set1_ps(w[2]),
               w3 = _mm_set1_ps(w[3]);
  for (int i = first; i < n; ++i) {
    const __m128 s = _mm_add_ps(_mm_add_ps(_mm_mul_ps(w0, _mm_load_ps(rows[0][i].v)),
                                           _mm_mul_ps(w1, _mm_load_ps(rows[1][i].v))),
                                _mm_add_ps(_mm_mul_ps(w2, _mm_load_ps(rows[2][i].v)),
                                           _mm_mul_ps(w3, _mm_load_ps(rows[3][i].v))));
    _mm_store_ps(out[i].v, s);
  }
#else
  for (int i = first; i < n; ++i)
    for (int c = 0; c < 4; ++c)
      out[i].v[c] = (w[0] * rows[0][i].v[c] + w[1] * rows[1][i].v[c]) +
                    (w[2] * rows[2][i].v[c] + w[3] * rows[3][i].v[c]);
#endif
}

// sum += wS lerp(lerp(s00, s01, lw), lerp(s10, s11, lw), nw), s01 = s00 + 1
// texel along mu_s.
inline void add_bilinear(const Rgb4* s0, const Rgb4* s1, float lw, float nw, const Rgb4& wS,
                         Rgb4& sum) {
#if defined(__SSE2__)
  const __m128 l1 = _mm_set1_ps(lw), l0 = _mm_set1_ps(1.0f - lw);
  const __m128 n1 = _mm_set1_ps(nw), n0 = _mm_set1_ps(1.0f - nw);
  const __m128 a = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s0[0].v)), _mm_mul_ps(l1, _mm_load_ps(s0[1].v)));
  const __m128 b = _mm_add_ps(_mm_mul_ps(l0, _mm_load_ps(s1[0].v)), _mm_mul_ps(l1, _mm_load_ps(s1[1].v)));
  const __m128 L = _mm_add_ps(_mm_mul_ps(n0, a), _mm_mul_ps(n1, b));
  _mm_store_ps(sum.v, _mm_add_ps(_mm_load_ps(sum.v), _mm_mul_ps(_mm_load_ps(wS.v), L)));
#else
  for (int c = 0; c < 4; ++c) {
    const float a = (1.0f - lw) * s0[0].v[c] + lw * s0[1].v[c];
    const float b = (1.0f - lw) * s1[0].v[c] + lw * s1[1].v[c];
    sum.v[c] += wS.v[c] * ((1.0f - nw) * a + nw * b);
  }
#endif
}

}  // namespace

// In single precision, three channels (and a pad) at a time: the table is
// float32 and a texel sums ~51 terms of one sign (relative rounding ~1e-6,
// far below the quadrature's error); the geometry (taps, weights) stays in
// double.
Texture bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                 const Texture& density, int nodes, const BakeContext& ctx) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const MuSAxis mu_s_axis(atm, shape);
  const Texture per_sigma_s = density_per_scattering(atm, shape, density);
  std::vector<Rgb4> radiance(per_sigma_s.texel_count());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, radiance.size()),
                    [&](const tbb::blocked_range<size_t>& ts) {
                      for (size_t t = ts.begin(); t != ts.end(); ++t)
                        for (int c = 0; c < 3; ++c)
                          radiance[t].v[c] = per_sigma_s.data[3 * t + c];
                    });
  const int W = shape.texture_width(), n_mu_s = shape.mu_s_size;
  auto row_of = [&](int y, int z) { return &radiance[(size_t(z) * shape.mu_size + y) * W]; };
  Texture out(W, shape.mu_size, shape.r_size, 1, {"R", "G", "B"});
  const int rows = shape.r_size * shape.mu_size;
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RayTransfer transfer;
    std::vector<Rgb4> slice(W), sum(W);
    // Per texel of the row: its mu_s and nu (nu is constant along the ray,
    // and so are its slice taps); per node, the texels' mu_s there and
    // their mu_s taps, computed for the whole row in one branch-free pass.
    std::vector<double> mu_s_x(W), nu_x(W), mu_s_node(W), tap_w(W);
    std::vector<int> tap_i0(W), nu_i0(W), nu_i1(W);
    std::vector<float> nu_w(W);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int z = row / shape.mu_size, y = row % shape.mu_size;
      ScatteringParams p0;
      for (int x = 0; x < W; ++x) {
        const ScatteringParams p = texels.at(x, y, z);
        if (x == 0) p0 = p;
        mu_s_x[x] = p.mu_s;
        nu_x[x] = p.nu;
        const AxisTap tn = scattering_taps(shape, {0.5 * (p.nu + 1.0), 0.5, 0.5, 0.5}).nu;
        nu_i0[x] = tn.i0 * n_mu_s;
        nu_i1[x] = tn.i1 * n_mu_s;
        nu_w[x] = float(tn.w);
      }
      const double r = p0.r, mu = p0.mu;
      const bool hits = p0.ray_hits_ground;
      ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, hits), nodes, transfer);
      std::fill(sum.begin(), sum.end(), Rgb4{});
      for (const TransferNode& q : transfer.nodes) {
        const glm::dvec3 wS = q.weight * sample_medium(atm, q.r - rb).scattering;
        if (wS == glm::dvec3(0.0)) continue;
        const Rgb4 wS4{{float(wS.r), float(wS.g), float(wS.b), 0.0f}};
        const double r_i = q.r, mu_i = mu_after(r, mu, q.s, r_i);
        const glm::dvec4 uvwz =
            scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r_i, mu_i, 1.0, 1.0, hits);
        // J / sigma_s at (r_i, mu_i) for every (mu_s, nu) texel: the
        // bilinear blend of four rows of the table, shared by the row's W
        // texels.
        const AxisTap tr = axis_tap(uvwz.w, shape.r_size), tm = axis_tap(uvwz.z, shape.mu_size);
        const Rgb4* rows4[4] = {row_of(tm.i0, tr.i0), row_of(tm.i1, tr.i0), row_of(tm.i0, tr.i1),
                                row_of(tm.i1, tr.i1)};
        const float w4[4] = {float((1.0 - tr.w) * (1.0 - tm.w)), float((1.0 - tr.w) * tm.w),
                             float(tr.w * (1.0 - tm.w)), float(tr.w * tm.w)};
        blend_rows(rows4, w4, W, slice.data());
        // clamp_cosine as min / max: the same value, no branch.
        for (int x = 0; x < W; ++x)
          mu_s_node[x] = std::min(std::max((r * mu_s_x[x] + q.s * nu_x[x]) / r_i, -1.0), 1.0);
        mu_s_axis.taps(mu_s_node.data(), W, tap_i0.data(), tap_w.data());
        for (int x = 0; x < W; ++x)
          add_bilinear(&slice[nu_i0[x] + tap_i0[x]], &slice[nu_i1[x] + tap_i0[x]],
                       float(tap_w[x]), nu_w[x], wS4, sum[x]);
      }
      float* texels_out = out.texel(0, y, z);
      for (int x = 0; x < W; ++x)
        for (int c = 0; c < 3; ++c) texels_out[3 * x + c] = sum[x].v[c];
      progress.tick();
    }
  });
  return out;
}

}  // namespace skybake

// The scattering density J_k of the 4D table: the direct quadrature and the
// fast path (Rayleigh from the incident field's moments, Mie over the
// directions in SSE). See scattering_orders.hpp for the equations and for
// how the work is shared between texels.
#include "atmosphere/scattering_density.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "atmosphere/phase.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// The view direction of (mu, nu) in the sun's frame: sun = (sin_s, 0, mu_s),
// view = (x, y, mu) with x sin_s + mu mu_s = nu, y >= 0 (J is symmetric in y).
glm::dvec3 view_direction(double mu, double mu_s, double nu) {
  const double sin_view = safe_sqrt(1.0 - mu * mu), sin_sun = safe_sqrt(1.0 - mu_s * mu_s);
  double x = sin_sun > 0.0 ? (nu - mu * mu_s) / sin_sun : sin_view;
  x = std::clamp(x, -sin_view, sin_view);
  return {x, safe_sqrt(sin_view * sin_view - x * x), mu};
}

// The six independent entries of a symmetric 3x3 matrix: xx yy zz xy xz yz.
inline void outer6(const glm::dvec3& v, double out[6]) {
  out[0] = v.x * v.x;
  out[1] = v.y * v.y;
  out[2] = v.z * v.z;
  out[3] = v.x * v.y;
  out[4] = v.x * v.z;
  out[5] = v.y * v.z;
}
// v^T M v for M given by outer6 sums.
inline double quadratic_form(const double m[6], const glm::dvec3& v) {
  return m[0] * v.x * v.x + m[1] * v.y * v.y + m[2] * v.z * v.z +
         2.0 * (m[3] * v.x * v.y + m[4] * v.x * v.z + m[5] * v.y * v.z);
}

// The part of the Mie phase that does not cancel in the normalized
// quadrature: Cornette-Shanks (1 + c^2) / w^1.5, Henyey-Greenstein 1 / w^1.5,
// w = 1 + g^2 - 2 g c (phase.hpp up to constant factors), written
// w = (1 - g)^2 + 2 g (1 - c) so that it stays > 0 in single precision for
// g -> 1 (g = 0.999: w = 1e-6 in the forward direction, where 1 + g^2 - 2 g c
// would cancel to rounding noise or below zero).
struct MieKernel {
  double a = 1.0, b = 0.0;  // (1 - g)^2, 2 g
  bool cornette_shanks = true;
  explicit MieKernel(const ScatteringPhases& p)
      : a((1.0 - p.mie_g) * (1.0 - p.mie_g)),
        b(2.0 * p.mie_g),
        cornette_shanks(p.mie_phase == PhaseKind::cornette_shanks) {}
};

// The grid and one incident field as float arrays for the per-texel Mie
// loop: the one loop of the bake that runs (texels x directions) times, 0.5 G
// at default sizes, so it runs in SSE single precision (lanes accumulate
// ~64 terms each: relative rounding ~1e-6, well below the quadrature's
// error). The field is symmetric about the sun's vertical plane (azimuths m
// and azimuths - 1 - m hold the same radiance, compute_incident_radiance),
// so a direction and its mirror (x, -y, z) are one pair: one load of the
// field, and their two phases over one division,
//   k+ + k- = (n+ q- + n- q+) / (q+ q-),  k = n / q,  q = w^1.5.
// Pairs padded to a multiple of 4 with zero weights.
struct MieBatch {
  size_t n = 0;
  std::vector<size_t> first;  // grid index of each pair's direction with y > 0
  std::vector<float> x, y, z, dw, lr, lg, lb;

  explicit MieBatch(const SphereGrid& grid) {
    const int half = grid.azimuths / 2;
    for (int l = 0; l < grid.bands; ++l)
      for (int m = 0; m < half; ++m) first.push_back(size_t(l) * grid.azimuths + m);
    n = (first.size() + 3) / 4 * 4;
    for (auto* v : {&x, &y, &z, &dw, &lr, &lg, &lb}) v->assign(n, 0.0f);
    for (size_t k = 0; k < first.size(); ++k) {
      const glm::dvec3& w = grid.directions[first[k]];
      x[k] = float(w.x);
      y[k] = float(w.y);
      z[k] = float(w.z);
      dw[k] = float(grid.solid_angle[first[k]]);
    }
    grid_azimuths = grid.azimuths;
  }
  // The pair's mean radiance (the two are equal for the density's fields).
  void set_field(const std::vector<glm::dvec3>& L) {
    for (size_t k = 0; k < first.size(); ++k) {
      const size_t j = first[k], mirror = j + grid_azimuths - 1 - 2 * (j % grid_azimuths);
      const glm::dvec3 mean = 0.5 * (L[j] + L[mirror]);
      lr[k] = float(mean.r * dw[k]);
      lg[k] = float(mean.g * dw[k]);
      lb[k] = float(mean.b * dw[k]);
    }
  }
  // sum_j k(v . w_j) L_j dw_j (RGB) and sum_j k(v . w_j) dw_j (out[3]),
  // over both directions of every pair.
  void sums(const MieKernel& k, const glm::dvec3& v, double out[4]) const {
    float lanes[4][4];
#if defined(__SSE2__)
    const __m128 vx = _mm_set1_ps(float(v.x)), vy = _mm_set1_ps(float(v.y)),
                 vz = _mm_set1_ps(float(v.z));
    const __m128 a = _mm_set1_ps(float(k.a)), b = _mm_set1_ps(float(k.b));
    const __m128 one = _mm_set1_ps(1.0f), zero = _mm_setzero_ps();
    const __m128 cs = _mm_set1_ps(k.cornette_shanks ? 1.0f : 0.0f);
    __m128 sr = _mm_setzero_ps(), sg = sr, sb = sr, sw = sr;
    for (size_t j = 0; j < n; j += 4) {
      const __m128 in_plane =
          _mm_add_ps(_mm_mul_ps(vx, _mm_loadu_ps(&x[j])), _mm_mul_ps(vz, _mm_loadu_ps(&z[j])));
      const __m128 across = _mm_mul_ps(vy, _mm_loadu_ps(&y[j]));
      const __m128 cp = _mm_add_ps(in_plane, across), cm = _mm_sub_ps(in_plane, across);
      const __m128 wp = _mm_add_ps(a, _mm_mul_ps(b, _mm_max_ps(_mm_sub_ps(one, cp), zero)));
      const __m128 wm = _mm_add_ps(a, _mm_mul_ps(b, _mm_max_ps(_mm_sub_ps(one, cm), zero)));
      const __m128 qp = _mm_mul_ps(wp, _mm_sqrt_ps(wp)), qm = _mm_mul_ps(wm, _mm_sqrt_ps(wm));
      const __m128 np = _mm_add_ps(one, _mm_mul_ps(cs, _mm_mul_ps(cp, cp)));
      const __m128 nm = _mm_add_ps(one, _mm_mul_ps(cs, _mm_mul_ps(cm, cm)));
      const __m128 p = _mm_div_ps(_mm_add_ps(_mm_mul_ps(np, qm), _mm_mul_ps(nm, qp)),
                                  _mm_mul_ps(qp, qm));
      sr = _mm_add_ps(sr, _mm_mul_ps(p, _mm_loadu_ps(&lr[j])));
      sg = _mm_add_ps(sg, _mm_mul_ps(p, _mm_loadu_ps(&lg[j])));
      sb = _mm_add_ps(sb, _mm_mul_ps(p, _mm_loadu_ps(&lb[j])));
      sw = _mm_add_ps(sw, _mm_mul_ps(p, _mm_loadu_ps(&dw[j])));
    }
    _mm_storeu_ps(lanes[0], sr);
    _mm_storeu_ps(lanes[1], sg);
    _mm_storeu_ps(lanes[2], sb);
    _mm_storeu_ps(lanes[3], sw);
#else
    for (auto& lane : lanes)
      for (float& f : lane) f = 0.0f;
    const float fa = float(k.a), fb = float(k.b), fcs = k.cornette_shanks ? 1.0f : 0.0f;
    for (size_t j = 0; j < n; j += 4)
      for (int l = 0; l < 4; ++l) {
        const float in_plane = float(v.x) * x[j + l] + float(v.z) * z[j + l];
        const float across = float(v.y) * y[j + l];
        const float cp = in_plane + across, cm = in_plane - across;
        const float wp = fa + fb * std::max(1.0f - cp, 0.0f);
        const float wm = fa + fb * std::max(1.0f - cm, 0.0f);
        const float qp = wp * std::sqrt(wp), qm = wm * std::sqrt(wm);
        const float p =
            ((1.0f + fcs * (cp * cp)) * qm + (1.0f + fcs * (cm * cm)) * qp) / (qp * qm);
        lanes[0][l] += p * lr[j + l];
        lanes[1][l] += p * lg[j + l];
        lanes[2][l] += p * lb[j + l];
        lanes[3][l] += p * dw[j + l];
      }
#endif
    for (int c = 0; c < 4; ++c)
      out[c] = (double(lanes[c][0]) + lanes[c][1]) + (double(lanes[c][2]) + lanes[c][3]);
  }

 private:
  size_t grid_azimuths = 0;
};

}  // namespace

glm::dvec3 compute_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                                      const ScatteringShape& shape, const ScatteringOrder& previous,
                                      const GroundIrradiance& ground, double r, double mu,
                                      double mu_s, double nu, int bands) {
  const ScatteringPhases phases = scattering_phases(atm);
  const SphereGrid grid = sphere_grid(bands);
  const std::vector<glm::dvec3> L =
      compute_incident_radiance(atm, transmittance_lut, shape, previous, ground, r, mu_s, grid);
  const glm::dvec3 view = view_direction(mu, mu_s, nu);
  glm::dvec3 sum_r(0.0), sum_m(0.0);
  double weight_r = 0.0, weight_m = 0.0;
  for (size_t j = 0; j < L.size(); ++j) {
    const double c = glm::dot(view, grid.directions[j]), dw = grid.solid_angle[j];
    const double p_r = phases.rayleigh(c) * dw, p_m = phases.mie(c) * dw;
    sum_r += p_r * L[j];
    weight_r += p_r;
    sum_m += p_m * L[j];
    weight_m += p_m;
  }
  glm::dvec3 sigma_r, sigma_m;
  scattering_by_group(atm, r - atm.bottom_radius_m, sigma_r, sigma_m);
  glm::dvec3 J(0.0);
  if (phases.has_rayleigh) J += sigma_r * sum_r / weight_r;
  if (phases.has_mie) J += sigma_m * sum_m / weight_m;
  return J;
}

Texture bake_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                                const ScatteringShape& shape, const ScatteringOrder& previous,
                                const GroundIrradiance& ground, int bands, const BakeContext& ctx) {
  const ScatteringPhases phases = scattering_phases(atm);
  const SphereGrid grid = sphere_grid(bands);
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const MieKernel mie_kernel(phases);
  const size_t n = grid.directions.size();
  // Moments of the grid itself (the normalization of the Rayleigh weights).
  double grid_w0 = 0.0, grid_w2[6] = {0, 0, 0, 0, 0, 0};
  for (size_t j = 0; j < n; ++j) {
    double o[6];
    outer6(grid.directions[j], o);
    grid_w0 += grid.solid_angle[j];
    for (int e = 0; e < 6; ++e) grid_w2[e] += o[e] * grid.solid_angle[j];
  }
  Texture out(shape.texture_width(), shape.mu_size, shape.r_size, 1, {"R", "G", "B"});
  // The band parts at each r texel, shared by its mu_s texels.
  std::vector<std::vector<std::vector<BandPart>>> parts(shape.r_size);
  tbb::parallel_for(0, shape.r_size,
                    [&](int z) { parts[z] = grid_band_parts(atm, texels.r[z], grid, previous); });
  const int pairs = shape.r_size * shape.mu_s_size;
  ProgressCounter progress(ctx, size_t(pairs));
  tbb::parallel_for(tbb::blocked_range<int>(0, pairs), [&](const tbb::blocked_range<int>& range) {
    MieBatch batch(grid);
    for (int pair = range.begin(); pair != range.end(); ++pair) {
      const int z = pair / shape.mu_s_size, l = pair % shape.mu_s_size;
      const double r = texels.r[z], mu_s = texels.mu_s[l];
      const std::vector<glm::dvec3> L = compute_incident_radiance(
          atm, transmittance_lut, shape, previous, ground, r, mu_s, grid, parts[z]);
      glm::dvec3 sigma_r, sigma_m;
      scattering_by_group(atm, r - atm.bottom_radius_m, sigma_r, sigma_m);
      const bool rayleigh = phases.has_rayleigh && sigma_r != glm::dvec3(0.0);
      const bool mie = phases.has_mie && sigma_m != glm::dvec3(0.0);
      // Rayleigh: sum_j (1 + (v.w_j)^2) L_j dw_j = A + v^T B v (3/(16 pi) cancels).
      glm::dvec3 moment0(0.0), moment2[6];
      for (int e = 0; e < 6; ++e) moment2[e] = glm::dvec3(0.0);
      if (mie) batch.set_field(L);
      for (size_t j = 0; j < n; ++j) {
        const glm::dvec3 Lw = L[j] * grid.solid_angle[j];
        double o[6];
        outer6(grid.directions[j], o);
        moment0 += Lw;
        for (int e = 0; e < 6; ++e) moment2[e] += o[e] * Lw;
      }
      for (int y = 0; y < shape.mu_size; ++y) {
        for (int m = 0; m < shape.nu_size; ++m) {
          const int x = m * shape.mu_s_size + l;
          const ScatteringParams p = texels.at(x, y, z);
          const glm::dvec3 v = view_direction(p.mu, p.mu_s, p.nu);
          glm::dvec3 J(0.0);
          if (rayleigh) {
            glm::dvec3 q = moment0;
            for (int c = 0; c < 3; ++c) {
              const double mc[6] = {moment2[0][c], moment2[1][c], moment2[2][c],
                                    moment2[3][c], moment2[4][c], moment2[5][c]};
              q[c] += quadratic_form(mc, v);
            }
            J += sigma_r * q / (grid_w0 + quadratic_form(grid_w2, v));
          }
          if (mie) {
            double sum[4];
            batch.sums(mie_kernel, v, sum);
            J += sigma_m * glm::dvec3(sum[0], sum[1], sum[2]) / sum[3];
          }
          float* texel = out.texel(x, y, z);
          for (int c = 0; c < 3; ++c) texel[c] = float(J[c]);
        }
      }
      progress.tick();
    }
  });
  return out;
}

}  // namespace skybake

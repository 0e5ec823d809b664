// The scattering density J_k of the 4D table: the direct quadrature and the
// fast path (Rayleigh from the incident field's moments, Mie over the
// directions in SIMD, mie_batch.hpp). See scattering_orders.hpp for the
// equations and for how the work is shared between texels.
#include "atmosphere/scattering_density.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/kernels/mie_batch.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/sun_frame_density.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// The view direction of (mu, nu) in the sun's frame: sun = (sin_s, 0, mu_s),
// view = (x, y, mu) with x sin_s + mu mu_s = nu, y >= 0 (J is symmetric in y).
// With sin_view = safe_sqrt(1 - mu^2) and sin_sun = safe_sqrt(1 - mu_s^2)
// given, for the nu slices of one (mu, mu_s).
glm::dvec3 view_direction(double mu, double mu_s, double nu, double sin_view, double sin_sun) {
  double x = sin_sun > 0.0 ? (nu - mu * mu_s) / sin_sun : sin_view;
  x = std::clamp(x, -sin_view, sin_view);
  return {x, safe_sqrt(sin_view * sin_view - x * x), mu};
}
glm::dvec3 view_direction(double mu, double mu_s, double nu) {
  return view_direction(mu, mu_s, nu, safe_sqrt(1.0 - mu * mu), safe_sqrt(1.0 - mu_s * mu_s));
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
  Texture out;
  bake_scattering_density(atm, transmittance_lut, shape, previous, ground, bands, ctx, out);
  return out;
}

namespace {

// What every (r, mu_s) pair of one density bake reads.
struct DensityBake {
  const Atmosphere& atm;
  const Texture& transmittance_lut;
  const ScatteringShape& shape;
  const ScatteringOrder& previous;
  const GroundIrradiance& ground;
  ScatteringPhases phases;
  SphereGrid grid;
  ScatteringTexelGrid texels;
  MieKernel mie_kernel;
  // Moments of the grid itself (the normalization of the Rayleigh weights).
  double grid_w0 = 0.0, grid_w2[6] = {0, 0, 0, 0, 0, 0};
  // The band parts at each r texel, shared by its mu_s texels.
  std::vector<std::vector<std::vector<BandPart>>> parts;
};

// Rayleigh: sum_j (1 + (v.w_j)^2) L_j dw_j = A + v^T B v (3/(16 pi) cancels):
// A = moment0, B from moment2 (outer6 entries).
struct FieldMoments {
  glm::dvec3 moment0{0.0}, moment2[6];
};

FieldMoments field_moments(const SphereGrid& grid, const std::vector<glm::dvec3>& L) {
  FieldMoments f;
  for (int e = 0; e < 6; ++e) f.moment2[e] = glm::dvec3(0.0);
  for (size_t j = 0; j < grid.directions.size(); ++j) {
    const glm::dvec3 Lw = L[j] * grid.solid_angle[j];
    double o[6];
    outer6(grid.directions[j], o);
    f.moment0 += Lw;
    for (int e = 0; e < 6; ++e) f.moment2[e] += o[e] * Lw;
  }
  return f;
}

// Rayleigh's J at view v, for scattering coefficient sigma_r.
glm::dvec3 rayleigh_density(const DensityBake& b, const FieldMoments& f, const glm::dvec3& sigma_r,
                            const glm::dvec3& v) {
  glm::dvec3 q = f.moment0;
  for (int c = 0; c < 3; ++c) {
    const double mc[6] = {f.moment2[0][c], f.moment2[1][c], f.moment2[2][c],
                          f.moment2[3][c], f.moment2[4][c], f.moment2[5][c]};
    q[c] += quadratic_form(mc, v);
  }
  return sigma_r * q / (b.grid_w0 + quadratic_form(b.grid_w2, v));
}

// What every view of one (r, mu_s) pair shares: the incident field, its
// moments and the groups' sigma_s; at(v) is J_k toward v.
class PairDensity {
 public:
  PairDensity(const DensityBake& b, MieBatch& batch, int z, int l) : b_(b), batch_(batch) {
    const double r = b.texels.r[z], mu_s = b.texels.mu_s[l];
    const std::vector<glm::dvec3> L = compute_incident_radiance(
        b.atm, b.transmittance_lut, b.shape, b.previous, b.ground, r, mu_s, b.grid, b.parts[z]);
    scattering_by_group(b.atm, r - b.atm.bottom_radius_m, sigma_r_, sigma_m_);
    rayleigh_ = b.phases.has_rayleigh && sigma_r_ != glm::dvec3(0.0);
    mie_ = b.phases.has_mie && sigma_m_ != glm::dvec3(0.0);
    if (mie_) batch.set_field(L);
    moments_ = field_moments(b.grid, L);
  }

  glm::dvec3 at(const glm::dvec3& v) const {
    glm::dvec3 J(0.0);
    if (rayleigh_) J += rayleigh_density(b_, moments_, sigma_r_, v);
    if (mie_) {
      double sum[4];
      batch_.sums(b_.mie_kernel, v, sum);
      J += sigma_m_ * glm::dvec3(sum[0], sum[1], sum[2]) / sum[3];
    }
    return J;
  }

 private:
  const DensityBake& b_;
  MieBatch& batch_;
  FieldMoments moments_;
  glm::dvec3 sigma_r_, sigma_m_;
  bool rayleigh_ = false, mie_ = false;
};

// Every (mu, nu) texel of the pair (r texel z, mu_s texel l).
void bake_density_pair(const DensityBake& b, MieBatch& batch, int z, int l, Texture& out) {
  const ScatteringShape& shape = b.shape;
  const PairDensity density(b, batch, z, l);
  const double mu_s = b.texels.mu_s[l], sin_sun = safe_sqrt(1.0 - mu_s * mu_s);
  for (int y = 0; y < shape.mu_size; ++y) {
    // texels.params(x, y, z) of the row's nu slices, with what they share once.
    const double mu = b.texels.mu[size_t(z) * shape.mu_size + y];
    const double spread = ScatteringTexelGrid::spread(mu, mu_s);
    const double sin_view = safe_sqrt(1.0 - mu * mu);
    double nu_before = 0.0;
    for (int m = 0; m < shape.nu_size; ++m) {
      const int x = m * shape.mu_s_size + l;
      const double nu = std::clamp(b.texels.nu[m], mu * mu_s - spread, mu * mu_s + spread);
      // A slice clamped to the nu of the one before is its view: its J.
      if (m > 0 && nu == nu_before) {
        std::copy_n(out.texel(x - shape.mu_s_size, y, z), 3, out.texel(x, y, z));
        continue;
      }
      nu_before = nu;
      const glm::dvec3 J = density.at(view_direction(mu, mu_s, nu, sin_view, sin_sun));
      float* texel = out.texel(x, y, z);
      for (int c = 0; c < 3; ++c) texel[c] = float(J[c]);
    }
  }
}

// Every (nu, cos_phi) texel of the pair (r texel z, mu_s texel l) of the
// table in the sun's frame.
void bake_sun_frame_pair(const DensityBake& b, MieBatch& batch, int z, int l,
                         SunFrameDensity& out) {
  const PairDensity density(b, batch, z, l);
  const double mu_s = b.texels.mu_s[l];
  for (int m = 0; m < out.nu_count(); ++m)
    for (int p = 0; p < out.phi_size; ++p) {
      const glm::dvec3 J =
          density.at(sun_frame_view(mu_s, out.nu[m], sun_frame_cos_phi(p, out.phi_size)));
      Rgb4& texel = out.texels[out.index(z, m, l, p)];
      texel = Rgb4{{float(J.r), float(J.g), float(J.b), 0.0f}};
    }
}

DensityBake make_density_bake(const Atmosphere& atm, const Texture& transmittance_lut,
                              const ScatteringShape& shape, const ScatteringOrder& previous,
                              const GroundIrradiance& ground, int bands) {
  const ScatteringPhases phases = scattering_phases(atm);
  DensityBake b{atm,    transmittance_lut,  shape,
                previous, ground,           phases,
                sphere_grid(bands), scattering_texel_grid(atm, shape), MieKernel(phases),
                0.0,      {0, 0, 0, 0, 0, 0}, {}};
  for (size_t j = 0; j < b.grid.directions.size(); ++j) {
    double o[6];
    outer6(b.grid.directions[j], o);
    b.grid_w0 += b.grid.solid_angle[j];
    for (int e = 0; e < 6; ++e) b.grid_w2[e] += o[e] * b.grid.solid_angle[j];
  }
  b.parts.resize(size_t(shape.r_size));
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    b.parts[z] = grid_band_parts(atm, b.texels.r[z], b.grid, previous);
  });
  return b;
}

// pair_bake(batch, z, l) for every (r, mu_s) pair, in parallel.
template <class PairBake>
void for_each_density_pair(const DensityBake& b, const BakeContext& ctx, PairBake&& pair_bake) {
  const int pairs = b.shape.r_size * b.shape.mu_s_size;
  ProgressCounter progress(ctx, size_t(pairs));
  tbb::parallel_for(tbb::blocked_range<int>(0, pairs), [&](const tbb::blocked_range<int>& range) {
    MieBatch batch(b.grid);
    for (int pair = range.begin(); pair != range.end(); ++pair) {
      pair_bake(batch, pair / b.shape.mu_s_size, pair % b.shape.mu_s_size);
      progress.tick();
    }
  });
}

}  // namespace

void bake_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                             const ScatteringShape& shape, const ScatteringOrder& previous,
                             const GroundIrradiance& ground, int bands, const BakeContext& ctx,
                             Texture& out) {
  const DensityBake b = make_density_bake(atm, transmittance_lut, shape, previous, ground, bands);
  reuse_rgb_table(out, shape);
  for_each_density_pair(b, ctx, [&](MieBatch& batch, int z, int l) {
    bake_density_pair(b, batch, z, l, out);
  });
}

void bake_sun_frame_density(const Atmosphere& atm, const Texture& transmittance_lut,
                            const ScatteringShape& shape, const ScatteringOrder& previous,
                            const GroundIrradiance& ground, int bands, int phi_size,
                            const BakeContext& ctx, SunFrameDensity& out) {
  const DensityBake b = make_density_bake(atm, transmittance_lut, shape, previous, ground, bands);
  out.shape = shape;
  out.phi_size = phi_size;
  out.nu = sun_frame_nu_grid(shape.nu_size);
  out.texels.resize(out.r_stride() * shape.r_size);  // every texel written
  for_each_density_pair(b, ctx, [&](MieBatch& batch, int z, int l) {
    bake_sun_frame_pair(b, batch, z, l, out);
  });
}

}  // namespace skybake

// Scattering orders of the 4D table: density, multiple scattering, the
// iteration and its outputs. See the header for the equations and for how
// the work is shared between texels.
#include "atmosphere/scattering_orders.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// Maps a stage's progress in [0, 1] onto [begin, end] of the whole bake.
BakeContext stage_context(const BakeContext& ctx, double begin, double end) {
  BakeContext sub;
  if (ctx.on_progress)
    sub.on_progress = [&ctx, begin, end](double f) { ctx.on_progress(begin + (end - begin) * f); };
  return sub;
}

// The view direction of (mu, nu) in the sun's frame: sun = (sin_s, 0, mu_s),
// view = (x, y, mu) with x sin_s + mu mu_s = nu, y >= 0 (J is symmetric in y).
glm::dvec3 view_direction(double mu, double mu_s, double nu) {
  const double sin_view = safe_sqrt(1.0 - mu * mu), sin_sun = safe_sqrt(1.0 - mu_s * mu_s);
  double x = sin_sun > 0.0 ? (nu - mu * mu_s) / sin_sun : sin_view;
  x = std::clamp(x, -sin_view, sin_view);
  return {x, safe_sqrt(sin_view * sin_view - x * x), mu};
}

glm::dvec3 sun_direction(double mu_s) {
  return {safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s};
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

// The grid and one incident field as float arrays, padded to a multiple of
// 4 with zero weights, for the per-texel Mie loop: the one loop of the bake
// that runs (texels x directions) times, 0.5 G at default sizes, so it runs
// 4 directions at a time in SSE single precision (lanes accumulate ~128
// terms each: relative rounding ~1e-6, well below the quadrature's error).
struct MieBatch {
  size_t n = 0;
  std::vector<float> x, y, z, dw, lr, lg, lb;

  explicit MieBatch(const SphereGrid& grid) : n((grid.directions.size() + 3) / 4 * 4) {
    for (auto* v : {&x, &y, &z, &dw, &lr, &lg, &lb}) v->assign(n, 0.0f);
    for (size_t j = 0; j < grid.directions.size(); ++j) {
      x[j] = float(grid.directions[j].x);
      y[j] = float(grid.directions[j].y);
      z[j] = float(grid.directions[j].z);
      dw[j] = float(grid.solid_angle[j]);
    }
  }
  void set_field(const std::vector<glm::dvec3>& L) {
    for (size_t j = 0; j < L.size(); ++j) {
      lr[j] = float(L[j].r * dw[j]);
      lg[j] = float(L[j].g * dw[j]);
      lb[j] = float(L[j].b * dw[j]);
    }
  }
  // sum_j k(v . w_j) L_j dw_j (RGB) and sum_j k(v . w_j) dw_j (out[3]).
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
      const __m128 c = _mm_add_ps(
          _mm_add_ps(_mm_mul_ps(vx, _mm_loadu_ps(&x[j])), _mm_mul_ps(vy, _mm_loadu_ps(&y[j]))),
          _mm_mul_ps(vz, _mm_loadu_ps(&z[j])));
      const __m128 w = _mm_add_ps(a, _mm_mul_ps(b, _mm_max_ps(_mm_sub_ps(one, c), zero)));
      const __m128 num = _mm_add_ps(one, _mm_mul_ps(cs, _mm_mul_ps(c, c)));
      const __m128 p = _mm_div_ps(num, _mm_mul_ps(w, _mm_sqrt_ps(w)));
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
        const float c = float(v.x) * x[j + l] + float(v.y) * y[j + l] + float(v.z) * z[j + l];
        const float w = fa + fb * std::max(1.0f - c, 0.0f);
        const float p = (1.0f + fcs * (c * c)) / (w * std::sqrt(w));
        lanes[0][l] += p * lr[j + l];
        lanes[1][l] += p * lg[j + l];
        lanes[2][l] += p * lb[j + l];
        lanes[3][l] += p * dw[j + l];
      }
#endif
    for (int c = 0; c < 4; ++c)
      out[c] = (double(lanes[c][0]) + lanes[c][1]) + (double(lanes[c][2]) + lanes[c][3]);
  }
};

void set_common_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                         const BrunetonTextures& out) {
  set_meta(meta, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(meta, "top_radius_m", atm.top_radius_m);
  set_meta(meta, "orders", out.orders_used);
  set_meta(meta, "last_residual", out.last_residual);
  set_meta(meta, "tolerance", spec.tolerance);
  set_meta(meta, "geometric_tail",
           spec.tolerance > 0.0 && spec.geometric_tail
               ? fmt::format("{:.17g},{:.17g},{:.17g}", out.tail_factor.x, out.tail_factor.y,
                             out.tail_factor.z)
               : std::string("none"));
  set_meta(meta, "units", std::string("relative to the sun_illuminance of the preset"));
}

std::string rgb_string(glm::dvec3 v) {
  return fmt::format("{:.17g},{:.17g},{:.17g}", v.x, v.y, v.z);
}

void set_scattering_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                             const BrunetonTextures& out, const ScatteringPhases& phases,
                             bool is_mie) {
  set_meta(meta, "parameterization", std::string("bruneton_4d_scattering"));
  set_common_metadata(meta, atm, spec, out);
  set_scattering_shape_metadata(meta, out.shape);
  set_meta(
      meta, "channel_layout",
      std::string("width = nu_size*mu_s_size, height = mu_size, depth = r_size; texel (x, y, "
                  "z): nu index x / mu_s_size, mu_s index x % mu_s_size, mu index y, r index z"));
  set_meta(
      meta, "mapping",
      std::string(
          "coord(x, n) = 0.5/n + x*(1 - 1/n); H = sqrt(Rt^2 - Rb^2), rho = sqrt(r^2 - Rb^2); "
          "u_r = coord(rho/H, r_size); ground rays: d = -r*mu - sqrt(r^2*(mu^2 - 1) + Rb^2), "
          "u_mu = 0.5 - 0.5*coord((d - (r - Rb))/(rho - (r - Rb)), mu_size/2) (0 when rho == r "
          "- Rb); other rays: d = -r*mu + sqrt(r^2*(mu^2 - 1) + Rt^2), u_mu = 0.5 + "
          "0.5*coord((d - (Rt - r))/(rho + H - (Rt - r)), mu_size/2); a(m) = (-Rb*m + "
          "sqrt(Rb^2*m^2 + H^2) - (Rt - Rb))/(H - (Rt - Rb)), A = a(mu_s_min), u_mu_s = "
          "coord(max(1 - a(mu_s)/A, 0)/(1 + a(mu_s)), mu_s_size); u_nu = (nu + 1)/2, slice k "
          "at nu = -1 + 2k/(nu_size - 1), lerp between slices (Bruneton 2017)"));
  set_meta(meta, "rayleigh_scattering_per_m", rgb_string(phases.rayleigh_per_m));
  set_meta(meta, "mie_scattering_per_m", rgb_string(phases.mie_per_m));
  set_meta(meta, "mie_phase",
           std::string(phases.mie_phase == PhaseKind::henyey_greenstein ? "henyey_greenstein"
                                                                        : "cornette_shanks"));
  set_meta(meta, "mie_g", phases.mie_g);
  set_meta(meta, "ray_nodes", spec.ray_nodes);
  set_meta(meta, "density_directions", spec.density_directions);
  if (is_mie) {
    set_meta(meta, "quantity",
             std::string("single Mie scattering without its phase function, RGB; radiance = "
                         "p_M(nu) * RGB"));
    return;
  }
  set_meta(meta, "mie_in_alpha", std::string(spec.combined_mie_alpha ? "true" : "false"));
  set_meta(
      meta, "quantity",
      std::string(spec.combined_mie_alpha
                      ? "RGB: single Rayleigh scattering without phase + multiple scattering / "
                        "p_R(nu); A: single Mie red without phase; radiance = p_R(nu)*RGB + "
                        "p_M(nu)*mie, mie = RGB*(A/R)*(beta_R.r/beta_M.r)*(beta_M/beta_R) "
                        "(Bodare & Sandberg eq. 19)"
                      : "RGB: single Rayleigh scattering without phase + multiple scattering "
                        "/ p_R(nu); radiance = p_R(nu)*RGB + p_M(nu)*single_mie"));
}

void set_irradiance_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                             const BrunetonTextures& out, const std::string& quantity) {
  set_meta(meta, "parameterization", std::string("bruneton_irradiance"));
  set_common_metadata(meta, atm, spec, out);
  set_meta(meta, "quantity", quantity);
  set_meta(meta, "width", spec.irradiance_width);
  set_meta(meta, "height", spec.irradiance_height);
  set_meta(meta, "mapping",
           std::string("coord(x, n) = 0.5/n + x*(1 - 1/n); u = coord(0.5 + 0.5*mu_s, width), "
                       "v = coord((r - Rb)/(Rt - Rb), height)"));
  set_meta(meta, "sun_angular_radius_rad", atm.sun_angular_radius_rad);
}

}  // namespace

// ---- Spec ----

void check_bruneton_spec(const BrunetonSpec& spec) {
  check_scattering_shape(spec.shape());
  if (spec.orders < 1 || spec.orders > kMaxScatteringOrders)
    throw Error(fmt::format("scattering: expected orders in [1, {}], got {}", kMaxScatteringOrders,
                            spec.orders));
  if (!(spec.tolerance >= 0.0) || !std::isfinite(spec.tolerance))
    throw Error(fmt::format("scattering: expected tolerance >= 0, got {}", spec.tolerance));
  if (spec.tolerance > 0.0 && (spec.max_orders < 2 || spec.max_orders > kMaxScatteringOrders))
    throw Error(fmt::format("scattering: expected max_orders in [2, {}], got {}",
                            kMaxScatteringOrders, spec.max_orders));
  if (spec.irradiance_width < 2 || spec.irradiance_height < 2)
    throw Error(fmt::format("irradiance: expected at least 2x2 texels, got {}x{}",
                            spec.irradiance_width, spec.irradiance_height));
  if (spec.ray_nodes < 2 || spec.density_directions < 2 || spec.irradiance_directions < 2)
    throw Error(fmt::format(
        "scattering: expected ray_nodes, density_directions and irradiance_directions >= 2, got "
        "{}, {}, {}",
        spec.ray_nodes, spec.density_directions, spec.irradiance_directions));
}

// ---- Density ----

glm::dvec3 GroundIrradiance::at(const Atmosphere& atm, const Texture& transmittance_lut,
                                double mu_s) const {
  if (table) return lookup_irradiance(*table, atm, atm.bottom_radius_m, mu_s);
  return compute_direct_irradiance(atm, transmittance_lut, atm.bottom_radius_m, mu_s);
}

SphereGrid sphere_grid(int bands) {
  SphereGrid g;
  g.bands = std::max(1, bands);
  g.azimuths = 2 * g.bands;
  const double d_theta = kPi / g.bands, d_phi = 2.0 * kPi / g.azimuths;
  for (int l = 0; l < g.bands; ++l) {
    const double theta = (l + 0.5) * d_theta;
    const double area = d_phi * (std::cos(l * d_theta) - std::cos((l + 1) * d_theta));
    for (int m = 0; m < g.azimuths; ++m) {
      const double phi = (m + 0.5) * d_phi;
      g.directions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                std::cos(theta));
      g.solid_angle.push_back(area);
    }
  }
  return g;
}

// See the header for the parts and why.
std::vector<BandPart> band_parts(const Atmosphere& atm, double r, double theta0, double theta1,
                                 bool with_transmittance) {
  const double rb = atm.bottom_radius_m;
  const double horizon = kPi - std::asin(std::min(1.0, rb / r));  // zenith angle of the horizon
  const double width = theta1 - theta0;
  const int steps = theta0 - width < horizon && horizon < theta1 + width ? kIncidentSubBands : 1;
  std::vector<double> cuts;
  for (int k = 0; k <= steps; ++k) cuts.push_back(theta0 + width * k / steps);
  if (horizon > theta0 && horizon < theta1) {
    cuts.push_back(horizon);
    std::sort(cuts.begin(), cuts.end());
  }
  const double band = std::cos(theta0) - std::cos(theta1);
  std::vector<BandPart> parts;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (!(cuts[k + 1] > cuts[k])) continue;
    BandPart p;
    p.theta = 0.5 * (cuts[k] + cuts[k + 1]);
    p.share = (std::cos(cuts[k]) - std::cos(cuts[k + 1])) / band;
    const double mu = std::cos(p.theta);
    p.hits = ray_intersects_ground(rb, r, mu);
    if (p.hits) p.d = distance_to_bottom_boundary(rb, r, mu);
    if (p.hits && with_transmittance)
      p.T_ground = ray_transmittance(atm, r, mu, p.d, kGroundRayNodes);
    parts.push_back(p);
  }
  return parts;
}

std::vector<glm::dvec3> ground_row_opacity(const Atmosphere& atm, const ScatteringShape& shape) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  std::vector<glm::dvec3> opacity(size_t(shape.r_size) * shape.mu_size, glm::dvec3(0.0));
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int y = 0; y < shape.mu_size; ++y) {
      const size_t row = size_t(z) * shape.mu_size + y;
      if (!texels.ray_hits_ground[row]) continue;
      const double r = texels.r[z], mu = texels.mu[row];
      const double d = distance_to_bottom_boundary(atm.bottom_radius_m, r, mu);
      opacity[row] = 1.0 - ray_transmittance(atm, r, mu, d, kGroundRayNodes);
    }
  });
  return opacity;
}

Texture divide_ground_rows_by_opacity(const Texture& table, const ScatteringShape& shape,
                                      const std::vector<glm::dvec3>& opacity) {
  Texture out = table;
  const int channels = std::min(out.channel_count(), 3);
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int y = 0; y < shape.mu_size; ++y) {
      const glm::dvec3 o = opacity[size_t(z) * shape.mu_size + y];
      if (o == glm::dvec3(0.0)) continue;  // a sky row (or a ray of zero length)
      for (int x = 0; x < shape.texture_width(); ++x) {
        float* texel = out.texel(x, y, z);
        for (int c = 0; c < channels; ++c) texel[c] = o[c] > 0.0 ? float(texel[c] / o[c]) : 0.0f;
      }
    }
  });
  return out;
}

std::vector<glm::dvec3> compute_incident_radiance(const Atmosphere& atm,
                                                  const Texture& transmittance_lut,
                                                  const ScatteringShape& shape,
                                                  const ScatteringOrder& previous,
                                                  const GroundIrradiance& ground, double r,
                                                  double mu_s, const SphereGrid& grid) {
  const double rb = atm.bottom_radius_m;
  const glm::dvec3 sun = sun_direction(mu_s);
  const glm::dvec3 albedo_over_pi = atm.ground_albedo / kPi;
  const bool ground_reflects = atm.ground_albedo != glm::dvec3(0.0);
  const double d_theta = kPi / grid.bands, d_phi = 2.0 * kPi / grid.azimuths;
  std::vector<glm::dvec3> L(grid.directions.size());
  for (int l = 0; l < grid.bands; ++l) {
    const std::vector<BandPart> parts =
        band_parts(atm, r, l * d_theta, (l + 1) * d_theta,
                   ground_reflects || previous.ground_rows_per_opacity);
    // Azimuths m and azimuths - 1 - m mirror each other about the sun's plane.
    for (int m = 0; m < grid.azimuths / 2; ++m) {
      const double phi = (m + 0.5) * d_phi;
      glm::dvec3 radiance(0.0);
      for (const BandPart& p : parts) {
        const glm::dvec3 w(std::sin(p.theta) * std::cos(phi), std::sin(p.theta) * std::sin(phi),
                           std::cos(p.theta));
        const double nu = glm::dot(w, sun);
        glm::dvec3 part = previous.radiance_at(atm, shape, r, w.z, mu_s, nu, p.hits);
        if (p.hits && previous.ground_rows_per_opacity) part *= 1.0 - p.T_ground;
        if (p.hits && ground_reflects) {
          const double mu_s_ground = clamp_cosine((r * mu_s + p.d * nu) / rb);
          part += p.T_ground * albedo_over_pi * ground.at(atm, transmittance_lut, mu_s_ground);
        }
        radiance += p.share * part;
      }
      L[size_t(l) * grid.azimuths + m] = radiance;
      L[size_t(l) * grid.azimuths + (grid.azimuths - 1 - m)] = radiance;
    }
  }
  return L;
}

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
  const int pairs = shape.r_size * shape.mu_s_size;
  ProgressCounter progress(ctx, size_t(pairs));
  tbb::parallel_for(tbb::blocked_range<int>(0, pairs), [&](const tbb::blocked_range<int>& range) {
    MieBatch batch(grid);
    for (int pair = range.begin(); pair != range.end(); ++pair) {
      const int z = pair / shape.mu_s_size, l = pair % shape.mu_s_size;
      const double r = texels.r[z], mu_s = texels.mu_s[l];
      const std::vector<glm::dvec3> L =
          compute_incident_radiance(atm, transmittance_lut, shape, previous, ground, r, mu_s, grid);
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

// ---- Multiple scattering ----

Texture density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                               const Texture& density) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  std::vector<glm::dvec3> sigma_s(shape.r_size);
  for (int z = 0; z < shape.r_size; ++z)
    sigma_s[z] = sample_medium(atm, texels.r[z] - atm.bottom_radius_m).scattering;
  Texture out = density;
  for (int c = 0; c < 3; ++c)
    for (int z = 0; z < shape.r_size; ++z) {
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

Texture bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                 const Texture& density, int nodes, const BakeContext& ctx) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const MuSAxis mu_s_axis(atm, shape);
  const Texture radiance = density_per_scattering(atm, shape, density);
  const int W = shape.texture_width(), n_mu_s = shape.mu_s_size;
  Texture out(W, shape.mu_size, shape.r_size, 1, {"R", "G", "B"});
  const int rows = shape.r_size * shape.mu_size;
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RayTransfer transfer;
    std::vector<double> slice(3 * size_t(W)), sum(3 * size_t(W));
    std::vector<ScatteringParams> params(W);
    std::vector<AxisTap> nu_taps(W);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int z = row / shape.mu_size, y = row % shape.mu_size;
      for (int x = 0; x < W; ++x) {
        params[x] = texels.at(x, y, z);
        nu_taps[x] = scattering_taps(shape, {0.5 * (params[x].nu + 1.0), 0.5, 0.5, 0.5}).nu;
      }
      const double r = params[0].r, mu = params[0].mu;
      const bool hits = params[0].ray_hits_ground;
      ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, hits), nodes, transfer);
      std::fill(sum.begin(), sum.end(), 0.0);
      for (const TransferNode& q : transfer.nodes) {
        const glm::dvec3 wS = q.weight * sample_medium(atm, q.r - rb).scattering;
        if (wS == glm::dvec3(0.0)) continue;
        const double r_i = q.r, mu_i = mu_after(r, mu, q.s, r_i);
        const glm::dvec4 uvwz =
            scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r_i, mu_i, 1.0, 1.0, hits);
        // J / sigma_s at (r_i, mu_i) for every (mu_s, nu) texel: the
        // bilinear blend of four rows of the table, shared by the row's W
        // texels.
        const AxisTap tr = axis_tap(uvwz.w, shape.r_size), tm = axis_tap(uvwz.z, shape.mu_size);
        const float* rows4[4] = {radiance.texel(0, tm.i0, tr.i0), radiance.texel(0, tm.i1, tr.i0),
                                 radiance.texel(0, tm.i0, tr.i1), radiance.texel(0, tm.i1, tr.i1)};
        const double w4[4] = {(1.0 - tr.w) * (1.0 - tm.w), (1.0 - tr.w) * tm.w, tr.w * (1.0 - tm.w),
                              tr.w * tm.w};
        for (size_t i = 0; i < slice.size(); ++i)
          slice[i] =
              w4[0] * rows4[0][i] + w4[1] * rows4[1][i] + w4[2] * rows4[2][i] + w4[3] * rows4[3][i];
        for (int x = 0; x < W; ++x) {
          const ScatteringParams& p = params[x];
          const double mu_s_i = clamp_cosine((r * p.mu_s + q.s * p.nu) / r_i);
          const AxisTap tl = mu_s_axis.tap(mu_s_i), tn = nu_taps[x];
          const double* s00 = &slice[3 * size_t(tn.i0 * n_mu_s + tl.i0)];
          const double* s01 = &slice[3 * size_t(tn.i0 * n_mu_s + tl.i1)];
          const double* s10 = &slice[3 * size_t(tn.i1 * n_mu_s + tl.i0)];
          const double* s11 = &slice[3 * size_t(tn.i1 * n_mu_s + tl.i1)];
          for (int c = 0; c < 3; ++c) {
            const double L = (1.0 - tn.w) * ((1.0 - tl.w) * s00[c] + tl.w * s01[c]) +
                             tn.w * ((1.0 - tl.w) * s10[c] + tl.w * s11[c]);
            sum[3 * size_t(x) + c] += wS[c] * L;
          }
        }
      }
      float* texels_out = out.texel(0, y, z);
      for (size_t i = 0; i < sum.size(); ++i) texels_out[i] = float(sum[i]);
      progress.tick();
    }
  });
  return out;
}

// ---- The iteration ----

BrunetonTextures bake_bruneton(const Atmosphere& atm, const Texture& transmittance_lut,
                               const BrunetonSpec& spec, const BakeContext& ctx) {
  check_bruneton_spec(spec);
  if (transmittance_lut.channel_count() < 3 || transmittance_lut.width < 2 ||
      transmittance_lut.height < 2)
    throw Error(
        fmt::format("scattering: expected an RGB transmittance LUT of at least 2x2, got {} "
                    "with {} channels",
                    transmittance_lut.shape_string(), transmittance_lut.channel_count()));
  const ScatteringShape shape = spec.shape();
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const bool converge = spec.tolerance > 0.0;
  const bool tail_mode = converge && spec.geometric_tail;
  const int last_order = converge ? spec.max_orders : spec.orders;
  const double stage = 1.0 / (last_order + 1);  // single, orders 2..N, final irradiance

  BrunetonTextures out;
  out.shape = shape;
  SingleScatteringTables single = bake_single_scattering(
      atm, transmittance_lut, shape, spec.ray_nodes, stage_context(ctx, 0.0, stage));
  Texture accumulated = single.rayleigh;  // RGB of the scattering texture
  const ScatteringOrder order1{&single.rayleigh, &single.mie, nullptr, &phases};
  Texture irradiance(spec.irradiance_width, spec.irradiance_height, 1, 1, {"R", "G", "B"});

  // The phases of each texel: Mie at the texel's own nu (clamped to what its
  // mu and mu_s allow), Rayleigh at its slice's nu before that clamp, for the
  // / p_R of the orders >= 2 and the residual (header, "Storage of orders
  // >= 2").
  const size_t texel_count = accumulated.texel_count();
  std::vector<float> phase_r(texel_count), phase_m(texel_count);
  tbb::parallel_for(tbb::blocked_range<int>(0, shape.r_size),
                    [&](const tbb::blocked_range<int>& zs) {
                      for (int z = zs.begin(); z != zs.end(); ++z)
                        for (int y = 0; y < shape.mu_size; ++y)
                          for (int x = 0; x < shape.texture_width(); ++x) {
                            const size_t t = accumulated.index(x, y, z) / 3;
                            phase_r[t] = float(phases.rayleigh(texels.nu[x / shape.mu_s_size]));
                            phase_m[t] = float(phases.mie(texels.at(x, y, z).nu));
                          }
                    });

  Texture previous_radiance;  // DeltaS of the previous order (k >= 3)
  glm::dvec3 previous_order_sum(0.0), previous_tail_factor(0.0);
  Texture ground_table;  // E_{k-2} for k >= 3
  ScatteringOrder previous = order1;
  GroundIrradiance ground;  // direct sunlight for order 2
  out.orders_used = 1;
  // The density reads the previous order with its ground rows per opacity
  // (header, ground_row_opacity); the irradiance reads only the sky.
  const std::vector<glm::dvec3> opacity = ground_row_opacity(atm, shape);
  const Texture single_r_per_opacity =
      divide_ground_rows_by_opacity(single.rayleigh, shape, opacity);
  const Texture single_m_per_opacity = divide_ground_rows_by_opacity(single.mie, shape, opacity);
  Texture previous_per_opacity;
  for (int k = 2; k <= last_order; ++k) {
    const double begin = (k - 1) * stage;
    ScatteringOrder density_previous{&single_r_per_opacity, &single_m_per_opacity, nullptr, &phases,
                                     true};
    if (k >= 3) {
      previous_per_opacity = divide_ground_rows_by_opacity(previous_radiance, shape, opacity);
      density_previous = ScatteringOrder{nullptr, nullptr, &previous_per_opacity, &phases, true};
    }
    const Texture density = bake_scattering_density(
        atm, transmittance_lut, shape, density_previous, ground, spec.density_directions,
        stage_context(ctx, begin, begin + 0.45 * stage));
    Texture E =
        bake_indirect_irradiance(atm, shape, previous, spec.irradiance_width,
                                 spec.irradiance_height, spec.irradiance_directions, BakeContext{});
    for (size_t i = 0; i < irradiance.data.size(); ++i) irradiance.data[i] += E.data[i];
    Texture delta =
        bake_multiple_scattering(atm, shape, density, spec.ray_nodes,
                                 stage_context(ctx, begin + 0.5 * stage, begin + stage));

    // Residual (header): peak of L_{<=k}, then the largest relative change.
    auto radiance = [&](size_t t, int c) {
      return double(phase_r[t]) * accumulated.data[3 * t + c] +
             double(phase_m[t]) * single.mie.data[3 * t + c] + double(delta.data[3 * t + c]);
    };
    double peak = 0.0;
    for (size_t t = 0; t < texel_count; ++t)
      for (int c = 0; c < 3; ++c) peak = std::max(peak, radiance(t, c));
    const double floor = std::max(1e-6 * peak, std::numeric_limits<double>::min());
    // The geometric tail (header): the ratio of this order's total to the
    // last's, per channel, and the tail factor f = lambda / (1 - lambda).
    glm::dvec3 order_sum(0.0);
    for (size_t t = 0; t < texel_count; ++t)
      for (int c = 0; c < 3; ++c) order_sum[c] += delta.data[3 * t + c];
    glm::dvec3 tail_factor(0.0);
    for (int c = 0; c < 3 && k >= 3; ++c) {
      const double ratio = order_sum[c] > 0.0 ? order_sum[c] / previous_order_sum[c] : 0.0;
      tail_factor[c] = ratio < kMaxTailRatio ? ratio / (1.0 - ratio) : 0.0;
    }
    double residual = 0.0;
    for (size_t t = 0; t < texel_count; ++t)
      for (int c = 0; c < 3; ++c)
        residual =
            std::max(residual, double(delta.data[3 * t + c]) / std::max(radiance(t, c), floor));
    for (size_t t = 0; t < texel_count; ++t)
      for (int c = 0; c < 3; ++c)
        accumulated.data[3 * t + c] =
            float(accumulated.data[3 * t + c] + double(delta.data[3 * t + c]) / phase_r[t]);

    out.orders_used = k;
    out.last_residual = residual;
    out.residuals.push_back(residual);
    previous_order_sum = order_sum;
    previous_tail_factor = tail_factor;
    previous_radiance = std::move(delta);
    ground_table = std::move(E);
    previous = ScatteringOrder{nullptr, nullptr, &previous_radiance, &phases};
    ground.table = &ground_table;
    if (converge && residual < spec.tolerance) break;
  }
  if (tail_mode) {
    // Orders k > N stand as DeltaS_N lambda^(k - N): their sum is f DeltaS_N.
    out.tail_factor = previous_tail_factor;
    for (size_t t = 0; t < texel_count; ++t)
      for (int c = 0; c < 3; ++c)
        accumulated.data[3 * t + c] =
            float(accumulated.data[3 * t + c] +
                  previous_tail_factor[c] * double(previous_radiance.data[3 * t + c]) / phase_r[t]);
  }
  // The sky of the last order lights the ground too (header).
  const Texture E_last =
      bake_indirect_irradiance(atm, shape, previous, spec.irradiance_width, spec.irradiance_height,
                               spec.irradiance_directions, BakeContext{});
  for (size_t i = 0; i < irradiance.data.size(); ++i)
    irradiance.data[i] += E_last.data[i] * (1.0 + out.tail_factor[i % 3]);
  out.direct_irradiance = bake_direct_irradiance(atm, transmittance_lut, spec.irradiance_width,
                                                 spec.irradiance_height, BakeContext{});
  if (spec.irradiance_includes_direct)
    for (size_t i = 0; i < irradiance.data.size(); ++i)
      irradiance.data[i] += out.direct_irradiance.data[i];

  // Outputs.
  out.scattering = Texture(accumulated.width, accumulated.height, accumulated.depth, 1,
                           spec.combined_mie_alpha ? std::vector<std::string>{"R", "G", "B", "A"}
                                                   : std::vector<std::string>{"R", "G", "B"});
  const int channels = out.scattering.channel_count();
  for (size_t t = 0; t < texel_count; ++t) {
    for (int c = 0; c < 3; ++c) out.scattering.data[channels * t + c] = accumulated.data[3 * t + c];
    if (spec.combined_mie_alpha) out.scattering.data[channels * t + 3] = single.mie.data[3 * t];
  }
  out.single_mie = std::move(single.mie);
  out.irradiance = std::move(irradiance);
  set_scattering_metadata(out.scattering.metadata, atm, spec, out, phases, false);
  set_scattering_metadata(out.single_mie.metadata, atm, spec, out, phases, true);
  set_irradiance_metadata(
      out.irradiance.metadata, atm, spec, out,
      spec.irradiance_includes_direct
          ? "ground irradiance on a horizontal surface, direct sunlight + sky orders 1..orders"
          : "indirect ground irradiance on a horizontal surface from the sky, orders 1..orders "
            "(add direct_irradiance, or E_sun*T(r, mu_s)*c(mu_s) from the transmittance LUT)");
  set_irradiance_metadata(out.direct_irradiance.metadata, atm, spec, out,
                          "direct sunlight on a horizontal surface, E_sun*T(r, mu_s)*c(mu_s), "
                          "c the cosine averaged over the sun's disk");
  set_meta(out.irradiance.metadata, "includes_direct",
           std::string(spec.irradiance_includes_direct ? "true" : "false"));
  if (ctx.on_progress) ctx.on_progress(1.0);
  return out;
}

}  // namespace skybake

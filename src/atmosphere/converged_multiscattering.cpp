// Psi_ms from converged multiple scattering: the 4D order iteration in
// memory, then the mean of all its light over the sphere around each texel.
// See the header and docs/reference.md "Converged Psi_ms".
#include "atmosphere/converged_multiscattering.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "atmosphere/order_progress.hpp"
#include "atmosphere/psi_view_nodes.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

BrunetonSpec ConvergedMultiscatteringSpec::default_converged_bruneton_spec() {
  BrunetonSpec b;
  b.r_size = 16;
  b.mu_size = 64;
  b.mu_s_size = 16;
  b.nu_size = 8;
  b.tolerance = 1e-3;
  b.max_orders = 100;
  return b;
}

const char* psi_estimator_name(PsiEstimator e) {
  return e == PsiEstimator::relative ? "relative" : "mean";
}

double converged_mu_s_min(const Atmosphere& atm) {
  const double ratio = atm.bottom_radius_m / atm.top_radius_m;
  return std::max(-0.99, -safe_sqrt(1.0 - ratio * ratio) - 0.1);
}

namespace {

// sum_{k >= 2} DeltaS_k from the accumulated table: (RGB - S_R) p_R at the
// slice's nu (scattering_orders.hpp, "Storage of orders >= 2").
Texture orders_above_one(const Atmosphere& atm, const ScatteringShape& shape,
                         const ScatteringPhases& phases, const Texture& accumulated,
                         const Texture& single_rayleigh) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  Texture out(accumulated.width, accumulated.height, accumulated.depth, 1, {"R", "G", "B"});
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int y = 0; y < shape.mu_size; ++y)
      for (int x = 0; x < shape.texture_width(); ++x) {
        const double p_r = phases.rayleigh(texels.nu[size_t(x / shape.mu_s_size)]);
        const float* a = accumulated.texel(x, y, z);
        const float* s = single_rayleigh.texel(x, y, z);
        float* o = out.texel(x, y, z);
        for (int c = 0; c < 3; ++c) o[c] = float(std::max(double(a[c]) - s[c], 0.0) * p_r);
      }
  });
  return out;
}

}  // namespace

ConvergedField compute_converged_field(const Atmosphere& atm, const Texture& transmittance_lut,
                                       const ConvergedMultiscatteringSpec& spec,
                                       const BakeContext& ctx) {
  BrunetonSpec b = spec.bruneton;
  b.mu_s_min = std::min(converged_mu_s_min(atm), spec.mu_s_min_cap);
  b.combined_mie_alpha = false;         // single Mie in its own table
  b.irradiance_includes_direct = true;  // the ground's light of every order
  // The field reads its irradiance at the ground alone (the ground's light in
  // the density, ground_irradiance, the energy balance): the table's two rows
  // are the ground and the top, and the ground's row is the same at any height.
  b.irradiance_height = 2;
  BrunetonTextures t = bake_bruneton(atm, transmittance_lut, b, ctx);
  ConvergedField f;
  f.shape = t.shape;
  f.phases = scattering_phases(atm);
  f.multiple = orders_above_one(atm, f.shape, f.phases, t.scattering, t.single_rayleigh);
  f.single.rayleigh = std::move(t.single_rayleigh);
  f.single.mie = std::move(t.single_mie);
  f.ground_irradiance = std::move(t.irradiance);
  f.orders_used = t.orders_used;
  f.last_residual = t.last_residual;
  if (const glm::dvec3* b = find_meta<glm::dvec3>(t.scattering.metadata, "energy_out_over_in"))
    f.energy_out_over_in = *b;
  return f;
}

namespace {

// The cells of the grid's half (bands x azimuths / 2, band-major) that
// azimuths mirrored about the sun's plane share: cell m of a band and cell
// azimuths - 1 - m see the same light.
int half_cells(const SphereGrid& grid) {
  return grid.bands * (grid.azimuths / 2);
}

// The direction of half cell i in the sun's frame (its band's and azimuth's middle).
glm::dvec3 half_cell_direction(const SphereGrid& grid, int i) {
  const int half = grid.azimuths / 2;
  return grid.directions[size_t((i / half) * grid.azimuths + i % half)];
}

// L* / E in each half cell: the sky of every order and the ground's light,
// the share-weighted mean over the band's parts at the cell's azimuth.
std::vector<glm::dvec3> incident_light(const Atmosphere& atm, const ConvergedField& field,
                                       double r, double mu_s, const SphereGrid& grid) {
  const ScatteringOrder single{&field.single.rayleigh, &field.single.mie, nullptr, &field.phases};
  const ScatteringOrder multiple{nullptr, nullptr, &field.multiple, &field.phases};
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const glm::dvec3 albedo_over_pi = atm.ground_albedo / kPi;
  glm::dvec3 per_sun(0.0);
  for (int c = 0; c < 3; ++c)
    per_sun[c] = atm.sun_illuminance[c] > 0.0 ? 1.0 / atm.sun_illuminance[c] : 0.0;
  const double d_theta = kPi / grid.bands, d_phi = 2.0 * kPi / grid.azimuths;
  const int half = grid.azimuths / 2;
  std::vector<glm::dvec3> light(size_t(half_cells(grid)), glm::dvec3(0.0));
  for (int l = 0; l < grid.bands; ++l) {
    const std::vector<BandPart> parts =
        band_parts(atm, r, l * d_theta, (l + 1) * d_theta, /*with_transmittance=*/true);
    for (int m = 0; m < half; ++m) {
      const double phi = (m + 0.5) * d_phi;
      glm::dvec3 radiance(0.0);
      for (const BandPart& p : parts) {
        const glm::dvec3 w(std::sin(p.theta) * std::cos(phi), std::sin(p.theta) * std::sin(phi),
                           std::cos(p.theta));
        const double nu = clamp_cosine(glm::dot(w, sun));
        glm::dvec3 part = single.radiance_at(atm, field.shape, r, w.z, mu_s, nu, p.hits) +
                          multiple.radiance_at(atm, field.shape, r, w.z, mu_s, nu, p.hits);
        if (p.hits) {
          const double mu_s_ground = clamp_cosine((r * mu_s + p.d * nu) / atm.bottom_radius_m);
          part += p.T_ground * albedo_over_pi *
                  lookup_irradiance(field.ground_irradiance, atm, atm.bottom_radius_m, mu_s_ground);
        }
        radiance += p.share * part;
      }
      light[size_t(l * half + m)] = radiance * per_sun;
    }
  }
  return light;
}

// Psi_conv: the mean of L* / E over the sphere.
glm::dvec3 mean_light(const std::vector<glm::dvec3>& light, const PsiQuadrature& q) {
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < light.size(); ++i) sum += 2.0 * q.solid_angle[i] * light[i];
  return sum / (4.0 * kPi);
}

// The source of orders >= 2 toward each half cell v, j(v) = sum_c f_c
// int p_c(v . w) L*(w) dw / E with f_c = sigma_s,c / sigma_s (the kernel's
// rows), and single scattering's, s1(v) = Vis T_sun sum_c f_c p_c(nu), both
// per unit of sigma_s E as the runtime's Psi_ms. Channels that do not
// scatter at this altitude stay 0.
struct DirectionalSource {
  std::vector<glm::dvec3> multiple, single;
};
DirectionalSource directional_source(const Atmosphere& atm, const Texture& transmittance_lut,
                                     const std::vector<glm::dvec3>& light, const PsiQuadrature& q,
                                     double r, double mu_s) {
  glm::dvec3 rayleigh, mie;
  scattering_by_group(atm, r - atm.bottom_radius_m, rayleigh, mie);
  const glm::dvec3 sigma_s = rayleigh + mie;
  const glm::dvec3 sun_light = ray_intersects_ground(atm.bottom_radius_m, r, mu_s)
                                   ? glm::dvec3(0.0)
                                   : lookup_transmittance_to_top(transmittance_lut, atm, r, mu_s);
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const size_t n = light.size();
  DirectionalSource out{std::vector<glm::dvec3>(n, glm::dvec3(0.0)),
                        std::vector<glm::dvec3>(n, glm::dvec3(0.0))};
  for (size_t v = 0; v < n; ++v) {
    glm::dvec3 jr(0.0), jm(0.0);
    const double* kr = &q.kernel_rayleigh[v * n];
    const double* km = &q.kernel_mie[v * n];
    for (size_t k = 0; k < n; ++k) {
      jr += kr[k] * light[k];
      jm += km[k] * light[k];
    }
    const double nu = glm::dot(q.directions[v], sun);
    for (int c = 0; c < 3; ++c) {
      if (!(sigma_s[c] > 0.0)) continue;
      const double fr = rayleigh[c] / sigma_s[c], fm = mie[c] / sigma_s[c];
      out.multiple[v][c] = fr * jr[c] + fm * jm[c];
      out.single[v][c] = sun_light[c] * (fr * rayleigh_phase(nu) + fm * q.mie_phase(nu));
    }
  }
  return out;
}

// How much ground viewers look through the point along each zenith band of
// view directions v (pointing away from the viewer, so the viewer sits
// toward -v, in the mirrored band): viewers spread evenly over a flat ground
// and looking evenly around see the point along v in proportion to
// T / |mu|, T the light's transmittance from the point to the viewer and mu
// the zenith cosine of -v (|mu| >= 0.02 keeps grazing rays finite), 0 where
// -v misses the ground. Averaged over the band's parts, which are cut at the
// horizon: the weight jumps there, and a band's middle alone would give a
// band astride the horizon all or none of it.
std::vector<glm::dvec3> ground_viewers(const Atmosphere& atm, double r, const SphereGrid& grid) {
  const double d_theta = kPi / grid.bands;
  std::vector<glm::dvec3> viewers(size_t(grid.bands), glm::dvec3(0.0));
  for (int l = 0; l < grid.bands; ++l) {
    const int mirrored = grid.bands - 1 - l;
    for (const BandPart& p : band_parts(atm, r, mirrored * d_theta, (mirrored + 1) * d_theta,
                                        /*with_transmittance=*/true))
      if (p.hits) viewers[size_t(l)] += p.share * p.T_ground / std::max(-std::cos(p.theta), 0.02);
  }
  return viewers;
}

// Each direction's viewer weight g(v) dOmega_v (ground_viewers), plus
// `others` x their mean over the directions.
std::vector<glm::dvec3> viewer_weights(const Atmosphere& atm, const PsiQuadrature& q, double r,
                                       double others) {
  const std::vector<glm::dvec3> by_band = ground_viewers(atm, r, q.grid);
  const size_t per_band = size_t(q.grid.azimuths / 2), n = q.directions.size();
  std::vector<glm::dvec3> viewers(n);
  glm::dvec3 sum(0.0);
  for (size_t v = 0; v < n; ++v) {
    viewers[v] = q.solid_angle[v] * by_band[v / per_band];
    sum += viewers[v];
  }
  if (others > 0.0)
    for (size_t v = 0; v < n; ++v) viewers[v] += others * sum / double(n) * q.solid_angle[v];
  return viewers;
}

// The relative estimator's weights g(v) dOmega_v / q(v) per channel (0 for a
// channel with no source in any direction). Directions with no light at all
// would take every weight: q is floored far below anything visible.
std::vector<glm::dvec3> relative_weights(const DirectionalSource& s,
                                         const std::vector<glm::dvec3>& viewers) {
  std::vector<glm::dvec3> w(viewers.size(), glm::dvec3(0.0));
  for (int c = 0; c < 3; ++c) {
    double largest = 0.0;
    for (size_t v = 0; v < viewers.size(); ++v)
      largest = std::max(largest, s.single[v][c] + s.multiple[v][c]);
    if (!(largest > 0.0)) continue;
    const double floor = 1e-9 * largest;
    for (size_t v = 0; v < viewers.size(); ++v)
      w[v][c] = viewers[v][c] / std::max(s.single[v][c] + s.multiple[v][c], floor);
  }
  return w;
}

// Psi_rel (docs/reference.md "Converged Psi_ms", "The relative estimator"):
// per channel, the constant whose relative error against the whole source
// q(v) = s1(v) + j(v) averages to zero over the views of ground viewers,
// g(v) their weight (ground_viewers):
//   sum_v g(v) dOmega_v (Psi_rel - j(v)) / q(v) = 0, i.e.
//   Psi_rel = sum_v g(v) dOmega_v j(v) / q(v) / sum_v g(v) dOmega_v / q(v).
// A channel that does not scatter here (sigma_s = 0: the runtime multiplies
// Psi by 0) or has no source in any direction keeps the mean.
glm::dvec3 relative_fit(const DirectionalSource& s, const std::vector<glm::dvec3>& weights,
                        glm::dvec3 mean) {
  glm::dvec3 psi = mean;
  for (int c = 0; c < 3; ++c) {
    double num = 0.0, den = 0.0;
    for (size_t v = 0; v < weights.size(); ++v) {
      num += weights[v][c] * s.multiple[v][c];
      den += weights[v][c];
    }
    if (den > 0.0) psi[c] = num / den;
  }
  return psi;
}

// The view nodes' values (compute_converged_multiscattering_slices).
std::vector<glm::dvec3> view_node_values(const Atmosphere& atm, const DirectionalSource& s,
                                         const PsiQuadrature& q, double r, double mu_s,
                                         glm::dvec3 isotropic, PsiViewShape shape) {
  std::vector<glm::dvec3> w;
  if (q.estimator == PsiEstimator::relative) {
    w = relative_weights(s, viewer_weights(atm, q, r, kViewNodeOtherViews));
  } else {
    for (double a : q.solid_angle) w.push_back(glm::dvec3(a));
  }
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  std::vector<double> nu, mu_v;
  for (const glm::dvec3& d : q.directions) {
    nu.push_back(glm::dot(d, sun));
    mu_v.push_back(d.z);
  }
  return fit_view_nodes(nu, mu_v, s.multiple, w, isotropic, shape);
}

}  // namespace

PsiQuadrature psi_quadrature(const ConvergedMultiscatteringSpec& spec,
                             const ScatteringPhases& phases) {
  PsiQuadrature q;
  q.grid = sphere_grid(spec.bands);
  q.estimator = spec.estimator;
  q.phases = phases;
  const SphereGrid& g = q.grid;
  const int n = half_cells(g), half = g.azimuths / 2;
  for (int i = 0; i < n; ++i) {
    q.directions.push_back(half_cell_direction(g, i));
    q.solid_angle.push_back(g.solid_angle[size_t((i / half) * g.azimuths)]);
  }
  if (q.estimator != PsiEstimator::relative && spec.nu_slices == 0) return q;
  // Each view's phase over the full grid, normalised to one on the grid (an
  // isotropic L* then gives j = L* exactly, whatever the cells' size against
  // Mie's forward peak), folded onto the half cells (mirror pairs added).
  auto kernel = [&](auto phase) {
    std::vector<double> k(size_t(n) * size_t(n), 0.0);
    for (int v = 0; v < n; ++v) {
      double norm = 0.0;
      for (int l = 0; l < g.bands; ++l)
        for (int m = 0; m < g.azimuths; ++m) {
          const size_t cell = size_t(l * g.azimuths + m);
          const double p = phase(glm::dot(q.directions[size_t(v)], g.directions[cell])) *
                           g.solid_angle[cell];
          norm += p;
          k[size_t(v) * n + size_t(l * half + std::min(m, g.azimuths - 1 - m))] += p;
        }
      for (int i = 0; i < n; ++i) k[size_t(v) * n + size_t(i)] /= norm;
    }
    return k;
  };
  q.kernel_rayleigh = kernel([](double c) { return rayleigh_phase(c); });
  q.kernel_mie = kernel([&](double c) { return phases.has_mie ? phases.mie(c) : rayleigh_phase(c); });
  return q;
}

double PsiQuadrature::mie_phase(double nu) const {
  return phases.has_mie ? phases.mie(nu) : 0.0;
}

glm::dvec3 compute_converged_multiscattering(const Atmosphere& atm,
                                             const Texture& transmittance_lut,
                                             const ConvergedField& field, double r, double mu_s,
                                             const PsiQuadrature& q) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  if (mu_s < field.shape.mu_s_min) return glm::dvec3(0.0);
  const std::vector<glm::dvec3> light = incident_light(atm, field, r, mu_s, q.grid);
  const glm::dvec3 mean = mean_light(light, q);
  if (q.estimator == PsiEstimator::mean) return mean;
  const DirectionalSource s = directional_source(atm, transmittance_lut, light, q, r, mu_s);
  return relative_fit(s, relative_weights(s, viewer_weights(atm, q, r, 0.0)), mean);
}

std::vector<glm::dvec3> compute_converged_multiscattering_slices(
    const Atmosphere& atm, const Texture& transmittance_lut, const ConvergedField& field, double r,
    double mu_s, const PsiQuadrature& q, PsiViewShape shape) {
  if (shape.nu_nodes == 0)
    return {compute_converged_multiscattering(atm, transmittance_lut, field, r, mu_s, q)};
  if (q.kernel_rayleigh.empty())
    throw Error("compute_converged_multiscattering_slices: needs the phase kernels");
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  if (mu_s < field.shape.mu_s_min)
    return std::vector<glm::dvec3>(size_t(1 + shape.size()), glm::dvec3(0.0));
  const std::vector<glm::dvec3> light = incident_light(atm, field, r, mu_s, q.grid);
  const glm::dvec3 mean = mean_light(light, q);
  const DirectionalSource s = directional_source(atm, transmittance_lut, light, q, r, mu_s);
  const glm::dvec3 isotropic =
      q.estimator == PsiEstimator::mean
          ? mean
          : relative_fit(s, relative_weights(s, viewer_weights(atm, q, r, 0.0)), mean);
  std::vector<glm::dvec3> out{isotropic};
  for (const glm::dvec3& v : view_node_values(atm, s, q, r, mu_s, isotropic, shape))
    out.push_back(v);
  return out;
}

SourceRange converged_source_range(const Atmosphere& atm, const Texture& transmittance_lut,
                                   const ConvergedField& field, double r, double mu_s,
                                   const PsiQuadrature& q) {
  if (q.kernel_rayleigh.empty()) throw Error("converged_source_range: needs the phase kernels");
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  if (mu_s < field.shape.mu_s_min) return {};
  const std::vector<glm::dvec3> light = incident_light(atm, field, r, mu_s, q.grid);
  const DirectionalSource s = directional_source(atm, transmittance_lut, light, q, r, mu_s);
  SourceRange range{glm::dvec3(INFINITY), glm::dvec3(0.0)};
  for (const glm::dvec3& j : s.multiple) {
    range.min = glm::min(range.min, j);
    range.max = glm::max(range.max, j);
  }
  return range;
}

Texture bake_converged_multiscattering_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                           const MultiscatteringLutSpec& table,
                                           const ConvergedMultiscatteringSpec& spec,
                                           const BakeContext& ctx) {
  if (table.width < 2 || table.height < 2 || spec.bands < 2)
    throw Error(fmt::format(
        "multiscattering: expected a size of at least 2x2 and at least 2 bands, got {}x{}, {}",
        table.width, table.height, spec.bands));
  const ConvergedField field =
      compute_converged_field(atm, transmittance_lut, spec, stage_context(ctx, 0.0, 0.9));
  return converged_multiscattering_table(atm, transmittance_lut, table, spec, field,
                                         stage_context(ctx, 0.9, 1.0));
}

Texture converged_multiscattering_table(const Atmosphere& atm, const Texture& transmittance_lut,
                                        const MultiscatteringLutSpec& table,
                                        const ConvergedMultiscatteringSpec& spec,
                                        const ConvergedField& field, const BakeContext& ctx) {
  const MultiscatteringMapping mapping = multiscattering_mapping(table, atm);
  const PsiQuadrature quadrature = psi_quadrature(spec, field.phases);
  const PsiViewShape shape = spec.view_shape();
  Texture tex(table.width, table.height, 1 + (shape.nu_nodes > 0 ? shape.size() : 0), 1,
              {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(table.height));
  tbb::parallel_for(0, table.height, [&](int y) {
    for (int x = 0; x < table.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, multiscattering_texel_uv(table, x, y), table.width, table.height, mapping);
      const std::vector<glm::dvec3> psi = compute_converged_multiscattering_slices(
          atm, transmittance_lut, field, p.r, p.mu_s, quadrature, shape);
      for (size_t z = 0; z < psi.size(); ++z) {
        float* t = tex.texel(x, y, int(z));
        for (int c = 0; c < 3; ++c) t[c] = float(psi[z][c]);
      }
    }
    progress.tick();
  });
  Metadata& m = tex.metadata;
  set_meta(m, "parameterization", std::string("hillaire2020_multiscattering"));
  set_meta(m, "model", std::string("converged"));
  set_meta(m, "quantity",
           std::string("mean incident radiance of every order (sky and ground) per unit sun "
                       "illuminance, from the 4D order iteration (docs/reference.md "
                       "\"Converged Psi_ms\")"));
  set_multiscattering_axes_metadata(m, mapping, atm);
  const BrunetonSpec& b = spec.bruneton;
  set_meta(m, "scattering_shape",
           fmt::format("{}x{}x{}x{}", b.r_size, b.mu_size, b.mu_s_size, b.nu_size));
  set_meta(m, "mu_s_min", field.shape.mu_s_min);
  set_meta(m, "tolerance", b.tolerance);
  set_meta(m, "orders_used", field.orders_used);
  set_meta(m, "last_residual", field.last_residual);
  set_meta(m, "energy_out_over_in", field.energy_out_over_in);
  set_meta(m, "bands", spec.bands);
  set_meta(m, "estimator", std::string(psi_estimator_name(spec.estimator)));
  if (spec.nu_slices > 0) {
    set_meta(m, "nu_slices", spec.nu_slices);
    set_meta(m, "zenith_slices", spec.zenith_slices);
    set_meta(m, "view_slices",
             std::string("slice 0: isotropic Psi_ms; a view reads a(nu) + b(mu_v), nu = "
                         "cos(view ray, sun), mu_v = the view ray's zenith cosine at the point; "
                         "a: slices 1 + k, k + f = (0.5 - 0.5 nu)^(1/4) (nu_slices - 1); b: "
                         "slices 1 + nu_slices + k, k + f = (0.5 + 0.5 sign(mu_v) sqrt(|mu_v|)) "
                         "(zenith_slices - 1); linear between slices k and k + 1 "
                         "(docs/reference.md \"Psi_ms by view\")"));
  }
  set_multiscattering_convention_metadata(m, table.convention);
  return tex;
}

}  // namespace skybake

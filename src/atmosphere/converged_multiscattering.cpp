// Psi_ms from converged multiple scattering: the 4D order iteration in
// memory, then the mean of all its light over the sphere around each texel.
// See the header and docs/reference.md "Converged Psi_ms".
#include "atmosphere/converged_multiscattering.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/order_progress.hpp"
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
  b.mu_s_min = converged_mu_s_min(atm);
  b.combined_mie_alpha = false;         // single Mie in its own table
  b.irradiance_includes_direct = true;  // the ground's light of every order
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
  return f;
}

glm::dvec3 compute_converged_multiscattering(const Atmosphere& atm,
                                             const Texture& transmittance_lut,
                                             const ConvergedField& field, double r, double mu_s,
                                             const SphereGrid& grid) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  if (mu_s < field.shape.mu_s_min) return glm::dvec3(0.0);
  const ScatteringOrder single{&field.single.rayleigh, &field.single.mie, nullptr, &field.phases};
  const ScatteringOrder multiple{nullptr, nullptr, &field.multiple, &field.phases};
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const glm::dvec3 albedo_over_pi = atm.ground_albedo / kPi;
  const double d_theta = kPi / grid.bands, d_phi = 2.0 * kPi / grid.azimuths;
  glm::dvec3 sum(0.0);
  for (int l = 0; l < grid.bands; ++l) {
    const double band_solid_angle = d_phi * (std::cos(l * d_theta) - std::cos((l + 1) * d_theta));
    const std::vector<BandPart> parts =
        band_parts(atm, r, l * d_theta, (l + 1) * d_theta, /*with_transmittance=*/true);
    // Azimuths m and azimuths - 1 - m mirror each other about the sun's plane.
    for (int m = 0; m < grid.azimuths / 2; ++m) {
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
      sum += 2.0 * band_solid_angle * radiance;
    }
  }
  glm::dvec3 psi = sum / (4.0 * kPi);
  for (int c = 0; c < 3; ++c)
    psi[c] = atm.sun_illuminance[c] > 0.0 ? psi[c] / atm.sun_illuminance[c] : 0.0;
  return psi;
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
  const MultiscatteringMapping mapping = table.sun_mapping == SunMapping::terminator
                                             ? terminator_mapping(atm)
                                             : MultiscatteringMapping{};
  const SphereGrid grid = sphere_grid(spec.bands);
  Texture tex(table.width, table.height, 1, 1, {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(table.height));
  tbb::parallel_for(0, table.height, [&](int y) {
    for (int x = 0; x < table.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, table.width), texel_center(y, table.height)}, table.width,
          table.height, mapping);
      const glm::dvec3 psi =
          compute_converged_multiscattering(atm, transmittance_lut, field, p.r, p.mu_s, grid);
      float* t = tex.texel(x, y);
      for (int c = 0; c < 3; ++c) t[c] = float(psi[c]);
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
  set_meta(m, "bands", spec.bands);
  return tex;
}

}  // namespace skybake

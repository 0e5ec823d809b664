// Sky light products: the sky's irradiance as L2 spherical harmonics for
// every (sun zenith, altitude) (atmosphere/sky_irradiance.hpp,
// docs/runtime.md "Sky irradiance") and the sky as GGX-prefiltered cube
// maps for listed views (atmosphere/sky_environment.hpp, docs/runtime.md
// "Sky environment").

#include <fmt/format.h>

#include "atmosphere/order_progress.hpp"
#include "atmosphere/sky_environment.hpp"
#include "core/cube_map.hpp"
#include "core/ggx_prefilter.hpp"
#include "core/mip_chain.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "atmosphere/sky_light_source.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product_options.hpp"
#include "pipeline/product_tables.hpp"

namespace skybake {

bool sky_irradiance_reads_multiscattering(const OutputSpec& spec) {
  return option_string(spec, "radiance_source", "converged_field") == "multiscattering_table";
}

SkyIrradianceSpec sky_irradiance_spec(const OutputSpec& spec) {
  SkyIrradianceSpec s;
  s.width = spec.size.at(0);
  s.height = spec.size.at(1);
  s.max_sun_zenith_rad =
      option_double(spec, "max_sun_zenith_deg", s.max_sun_zenith_rad / kDeg) * kDeg;
  s.sky_only = spec.options.value("sky_only", false);
  s.steps = option_int(spec, "steps", s.steps);
  s.below = option_int(spec, "rays_below_horizon", s.below);
  s.above = option_int(spec, "rays_above_horizon", s.above);
  s.azimuths = option_int(spec, "azimuths", s.azimuths);
  return s;
}

SkyLightSourceSpec sky_light_source_spec(const OutputSpec& spec, const Atmosphere& atm,
                                         double deepest_sun_zenith_rad) {
  SkyLightSourceSpec s;
  s.field = sky_light_field_spec(spec, atm);
  s.deepest_sun_zenith_rad = deepest_sun_zenith_rad;
  const std::string twilight = option_string(spec, "twilight_source", "twilight_field");
  if (!sun_below_horizon(deepest_sun_zenith_rad) || twilight == "converged_field")
    s.twilight = TwilightSource::daylight_field;
  else if (twilight == "psi_ms_by_view")
    s.twilight = TwilightSource::psi_ms_by_view;
  return s;
}

SkyEnvironmentSpec sky_environment_spec(const OutputSpec& spec) {
  SkyEnvironmentSpec s;
  s.face = spec.size.at(0);
  s.levels = option_int(spec, "levels", s.levels);
  s.samples = option_int(spec, "ggx_samples", s.samples);
  s.steps = option_int(spec, "steps", s.steps);
  s.sky_only = spec.options.value("sky_only", false);
  if (auto it = spec.options.find("views"); it != spec.options.end() && it->is_array()) {
    for (const auto& v : *it)
      s.views.push_back({v.value("altitude_km", 0.0) * 1e3, v.value("sun_zenith_deg", 45.0) * kDeg});
  } else {
    // Noon-like and low sun at the ground (docs/runtime.md "Sky environment").
    s.views = {{0.0, 45.0 * kDeg}, {0.0, 85.0 * kDeg}};
  }
  return s;
}

void make_sky_light_held(SkyLightHeld& out, const Atmosphere& atm, const OutputSpec& spec,
                         const Texture& transmittance, const Texture& multiscattering,
                         const SkyIrradianceSpec& rays, double deepest_sun_zenith_rad,
                         const BakeContext& ctx) {
  if (sky_irradiance_reads_multiscattering(spec)) {
    out.psi_ms = psi_ms_source(atm, transmittance, multiscattering, rays);
    return;
  }
  SkyLightSourceSpec light = sky_light_source_spec(spec, atm, deepest_sun_zenith_rad);
  light.rays = rays;
  make_sky_light_source(out.light, atm, transmittance, light, ctx);
}

namespace {

// The held source for a product bake: its inputs from the product graph.
void make_product_sky_light(SkyLightHeld& out, const Scene& scene, const OutputSpec& spec,
                            const ProductInputs& in, const SkyIrradianceSpec& rays,
                            double deepest_sun_zenith_rad, const BakeContext& ctx) {
  make_sky_light_held(out, scene.atmosphere, spec, *in.at("transmittance"),
                      *in.at("multiscattering"), rays, deepest_sun_zenith_rad, ctx);
}

Texture bake_sky_environment_product(const Scene& scene, const OutputSpec& spec,
                                     const ProductInputs& in, const BakeContext& ctx) {
  SkyIrradianceSpec s;
  s.sky_only = spec.options.value("sky_only", false);
  s.steps = option_int(spec, "steps", s.steps);
  const SkyEnvironmentSpec e = sky_environment_spec(spec);
  double deepest = 0.0;
  for (const SkyEnvironmentView& v : e.views) deepest = std::max(deepest, v.sun_zenith_rad);
  SkyLightHeld held;
  make_product_sky_light(held, scene, spec, in, s, deepest, stage_context(ctx, 0.0, 0.5));
  return bake_sky_environment(scene.atmosphere, held.source(), e, stage_context(ctx, 0.5, 1.0));
}

// Levels 1.. of the cube's chain: GGX-prefiltered from level 0 (core/ggx_prefilter.hpp),
// half of each filtered and mirrored, as level 0 is symmetric about the sun's plane.
std::vector<Texture> sky_environment_lower_levels(const Texture& level0, const OutputSpec& spec) {
  const SkyEnvironmentSpec s = sky_environment_spec(spec);
  return ggx_prefilter_levels(level0, sky_environment_levels(s), s.samples, true);
}

std::vector<ProductProblem> sky_environment_problems(const OutputSpec& spec) {
  std::vector<ProductProblem> problems = equal_size_problems(spec, "cube map faces are square");
  const SkyEnvironmentSpec s = sky_environment_spec(spec);
  if (s.levels > mip_count(s.face, s.face))
    problems.push_back({"/levels", fmt::format("expected at most {} levels for {} x {} faces, got {}",
                                               mip_count(s.face, s.face), s.face, s.face, s.levels)});
  if (!sky_irradiance_reads_multiscattering(spec))
    for (ProductProblem& p : converged_field_problems(spec)) problems.push_back(std::move(p));
  return problems;
}

Texture bake_sky_irradiance_product(const Scene& scene, const OutputSpec& spec,
                                    const ProductInputs& in, const BakeContext& ctx) {
  const SkyIrradianceSpec s = sky_irradiance_spec(spec);
  SkyLightHeld held;
  // The fields' iterations are about half the bake (docs/decisions/sky-irradiance-source.md).
  make_product_sky_light(held, scene, spec, in, s, s.max_sun_zenith_rad,
                         stage_context(ctx, 0.0, 0.6));
  return bake_sky_irradiance(scene.atmosphere, held.source(), s, stage_context(ctx, 0.6, 1.0));
}

// The field's 4D table must be one bake_bruneton accepts.
std::vector<ProductProblem> sky_irradiance_problems(const OutputSpec& spec) {
  if (sky_irradiance_reads_multiscattering(spec)) return {};
  return converged_field_problems(spec);
}

}  // namespace

void add_sky_light_products(std::vector<ProductInfo>& r) {
  ProductInfo p = atmosphere_lut_product(
      "sky_irradiance",
      "sky and ground light as L2 SH radiance, (sun zenith, altitude) x 6 coefficients, "
      "Ramamoorthi & Hanrahan 2001",
      {"sun_zenith", "altitude"}, {32, 16}, {256, 256}, {"transmittance", "multiscattering"},
      bake_sky_irradiance_product, 280000.0);
  p.allowed_formats = {"exr", "dds", "ktx2"};
  p.check = sky_irradiance_problems;
  r.push_back(std::move(p));

  ProductInfo e = atmosphere_lut_product(
      "sky_environment",
      "the sky as HDR cube maps per listed view (altitude, sun), GGX-prefiltered mips for "
      "specular IBL, with their L2 SH",
      {"face", "face"}, {128, 128}, {1024, 1024}, {"transmittance", "multiscattering"},
      bake_sky_environment_product, 16000.0);
  e.default_formats = {"ktx2", "dds"};
  e.allowed_formats = {"dds", "ktx2"};
  e.half_files = true;
  e.cube_map = true;
  e.lower_levels = sky_environment_lower_levels;
  e.check = sky_environment_problems;
  r.push_back(std::move(e));
}

}  // namespace skybake

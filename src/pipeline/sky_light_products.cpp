// Sky light products: the sky's irradiance as L2 spherical harmonics for
// every (sun zenith, altitude) (atmosphere/sky_irradiance.hpp,
// docs/runtime.md "Sky irradiance").

#include "atmosphere/order_progress.hpp"
#include "atmosphere/sky_irradiance.hpp"
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

namespace {

Texture bake_sky_irradiance_product(const Scene& scene, const OutputSpec& spec,
                                    const ProductInputs& in, const BakeContext& ctx) {
  const Atmosphere& atm = scene.atmosphere;
  const Texture& transmittance = *in.at("transmittance");
  const SkyIrradianceSpec s = sky_irradiance_spec(spec);
  if (sky_irradiance_reads_multiscattering(spec)) {
    const SkyRadianceSource source = psi_ms_source(atm, transmittance, *in.at("multiscattering"), s);
    return bake_sky_irradiance(atm, source, s, ctx);
  }
  // The field's iteration is about half the bake (docs/decisions/sky-irradiance-source.md).
  const ConvergedField field = compute_converged_field(
      atm, transmittance, converged_multiscattering_spec(spec), stage_context(ctx, 0.0, 0.7));
  SkyRadianceSource source;
  source.transmittance = &transmittance;
  source.field = &field;
  return bake_sky_irradiance(atm, source, s, stage_context(ctx, 0.7, 1.0));
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
}

}  // namespace skybake

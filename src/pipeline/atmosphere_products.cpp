// Atmosphere products: presets in km and degrees become the bakers' SI specs
// here, once.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "atmosphere/order_progress.hpp"
#include "atmosphere/orders_resolution.hpp"
#include "atmosphere/sky_preview.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/table_conventions.hpp"
#include "pipeline/product_options.hpp"
#include "pipeline/product_tables.hpp"
#include "pipeline/runtime_metadata.hpp"
#include "pipeline/table_conventions.hpp"

namespace skybake {

namespace {


double json_number(const nlohmann::json& obj, const char* key, double fallback) {
  auto it = obj.find(key);
  return it != obj.end() && it->is_number() ? it->get<double>() : fallback;
}

Texture bake_transmittance(const Scene& scene, const OutputSpec& spec, const ProductInputs&,
                           const BakeContext& ctx) {
  return bake_transmittance_lut(scene.atmosphere, transmittance_spec(spec), ctx);
}

Texture bake_multiscattering(const Scene& scene, const OutputSpec& spec, const ProductInputs& in,
                             const BakeContext& ctx) {
  Texture tex;
  if (multiscattering_is_converged(spec)) {
    tex = bake_converged_multiscattering_lut(scene.atmosphere, *in.at("transmittance"),
                                             multiscattering_spec(spec),
                                             converged_multiscattering_spec(spec), ctx);
    // Converged orders scatter with the real phases (Hillaire's model is
    // isotropic and records none).
    set_mie_phase_metadata(scene.atmosphere, tex.metadata);
  } else {
    tex = bake_multiscattering_lut(scene.atmosphere, *in.at("transmittance"),
                                   multiscattering_spec(spec), ctx);
  }
  if (fits_demo_march(spec)) fit_to_demo_march(scene.atmosphere, *in.at("transmittance"), tex);
  return tex;
}

// Default layers: a viewer near the ground under 8 sun positions from the
// zenith to 10 degrees below the horizon.
std::vector<SkyviewView> default_skyview_views() {
  std::vector<SkyviewView> views;
  for (double zenith_deg : {0.0, 30.0, 60.0, 75.0, 85.0, 90.0, 95.0, 100.0})
    views.push_back({200.0, zenith_deg * kDeg});
  return views;
}

}  // namespace

TransmittanceLutSpec transmittance_spec(const OutputSpec& spec) {
  TransmittanceLutSpec lut;
  lut.width = spec.size.at(0);
  lut.height = spec.size.at(1);
  lut.steps = option_int(spec, "steps", lut.steps);
  lut.convention = output_convention(spec);
  return lut;
}

MultiscatteringLutSpec multiscattering_spec(const OutputSpec& spec) {
  MultiscatteringLutSpec lut;
  lut.width = spec.size.at(0);
  lut.height = spec.size.at(1);
  lut.directions = option_int(spec, "directions", lut.directions);
  lut.steps = option_int(spec, "steps", lut.steps);
  if (spec.options.value("sun_mapping", std::string("linear")) == "terminator")
    lut.sun_mapping = SunMapping::terminator;
  if (spec.options.value("altitude_mapping", std::string("linear")) == "quadratic")
    lut.altitude_mapping = AltitudeMapping::quadratic;
  if (spec.options.value("direction_quadrature", std::string("fibonacci")) == "symmetric_gauss")
    lut.quadrature = DirectionQuadrature::symmetric_gauss;
  lut.convention = output_convention(spec);
  return lut;
}

bool multiscattering_is_angular(const OutputSpec& spec) {
  return spec.options.value("angular", std::string("none")) == "nu_zenith";
}

bool multiscattering_is_converged(const OutputSpec& spec) {
  return spec.options.value("model", std::string("hillaire2020")) == "converged";
}

ConvergedMultiscatteringSpec converged_multiscattering_spec(const OutputSpec& spec) {
  ConvergedMultiscatteringSpec c;
  if (auto it = spec.options.find("scattering_shape"); it != spec.options.end() && it->is_array() &&
                                                       it->size() == 4) {
    c.bruneton.r_size = (*it)[0].get<int>();
    c.bruneton.mu_size = (*it)[1].get<int>();
    c.bruneton.mu_s_size = (*it)[2].get<int>();
    c.bruneton.nu_size = (*it)[3].get<int>();
  }
  c.bruneton.tolerance = option_double(spec, "tolerance", c.bruneton.tolerance);
  c.bands = option_int(spec, "bands", c.bands);
  c.estimator = spec.options.value("estimator", std::string("relative")) == "mean"
                    ? PsiEstimator::mean
                    : PsiEstimator::relative;
  if (multiscattering_is_angular(spec)) {
    c.nu_slices = option_int(spec, "nu_slices", kDefaultNuSlices);
    c.zenith_slices = option_int(spec, "zenith_slices", kDefaultZenithSlices);
  }
  return c;
}

bool skyview_uses_multiple4d(const OutputSpec& spec) {
  return spec.options.value("multiple_scattering", std::string("hillaire2020")) == "scattering4d";
}

namespace {

// The options carry the schema's default shape, which stands for "the
// default": refined where the Mie group shapes the orders.
bool has_default_field_shape(const BrunetonSpec& b) {
  const BrunetonSpec d = ConvergedMultiscatteringSpec::default_converged_bruneton_spec();
  return b.r_size == d.r_size && b.mu_size == d.mu_size && b.mu_s_size == d.mu_s_size &&
         b.nu_size == d.nu_size;
}

}  // namespace

ConvergedMultiscatteringSpec skyview_multiple4d_spec(const OutputSpec& spec,
                                                     const Atmosphere& atm) {
  ConvergedMultiscatteringSpec c = converged_multiscattering_spec(spec);
  if (has_default_field_shape(c.bruneton) && mie_shapes_multiple_scattering(atm))
    c.bruneton = with_mie_lobe_shape(c.bruneton);
  return c;
}

ConvergedMultiscatteringSpec sky_light_field_spec(const OutputSpec& spec, const Atmosphere& atm) {
  ConvergedMultiscatteringSpec c = converged_multiscattering_spec(spec);
  if (has_default_field_shape(c.bruneton)) c.bruneton = sky_light_field_shape(atm, c.bruneton);
  return c;
}

SkyviewLutSpec skyview_spec(const OutputSpec& spec) {
  SkyviewLutSpec lut;
  lut.width = spec.size.at(0);
  lut.height = spec.size.at(1);
  lut.steps = option_int(spec, "steps", lut.steps);
  lut.views.clear();
  if (auto it = spec.options.find("views"); it != spec.options.end() && it->is_array()) {
    for (const auto& v : *it)
      lut.views.push_back(
          {json_number(v, "altitude_km", 0.0) * 1e3, json_number(v, "sun_zenith_deg", 0.0) * kDeg});
  } else {
    lut.views = default_skyview_views();
  }
  lut.convention = output_convention(spec);
  return lut;
}

AerialPerspectiveSpec aerial_perspective_spec(const OutputSpec& spec) {
  AerialPerspectiveSpec lut;
  lut.width = spec.size.at(0);
  lut.height = spec.size.at(1);
  lut.depth = spec.size.at(2);
  lut.depth_range_m = option_double(spec, "depth_range_km", lut.depth_range_m * 1e-3) * 1e3;
  lut.steps_per_slice = option_int(spec, "steps_per_slice", lut.steps_per_slice);
  const nlohmann::json camera = spec.options.value("camera", nlohmann::json::object());
  lut.camera.altitude_m = json_number(camera, "altitude_km", lut.camera.altitude_m * 1e-3) * 1e3;
  lut.camera.yaw_rad = json_number(camera, "yaw_deg", 0.0) * kDeg;
  lut.camera.pitch_rad = json_number(camera, "pitch_deg", 0.0) * kDeg;
  lut.camera.vertical_fov_rad = json_number(camera, "vertical_fov_deg", 60.0) * kDeg;
  lut.camera.aspect = json_number(camera, "aspect", lut.camera.aspect);
  const nlohmann::json sun = spec.options.value("sun", nlohmann::json::object());
  lut.sun_zenith_rad = json_number(sun, "zenith_deg", 45.0) * kDeg;
  lut.sun_azimuth_rad = json_number(sun, "azimuth_deg", 0.0) * kDeg;
  lut.convention = output_convention(spec);
  return lut;
}

namespace {

Texture bake_skyview(const Scene& scene, const OutputSpec& spec, const ProductInputs& in,
                     const BakeContext& ctx) {
  if (skyview_uses_multiple4d(spec)) {
    const ConvergedField field =
        compute_converged_field(scene.atmosphere, *in.at("transmittance"),
                                skyview_multiple4d_spec(spec, scene.atmosphere),
                                stage_context(ctx, 0.0, 0.8));
    return bake_skyview_lut_multiple4d(scene.atmosphere, *in.at("transmittance"), field,
                                       skyview_spec(spec), stage_context(ctx, 0.8, 1.0));
  }
  return bake_skyview_lut(scene.atmosphere, *in.at("transmittance"), *in.at("multiscattering"),
                          skyview_spec(spec), ctx);
}

Texture bake_aerial_perspective(const Scene& scene, const OutputSpec& spec, const ProductInputs& in,
                                const BakeContext& ctx) {
  return bake_aerial_perspective_lut(scene.atmosphere, *in.at("transmittance"),
                                     *in.at("multiscattering"), aerial_perspective_spec(spec), ctx);
}

SkyPreviewSpec preview_spec(const OutputSpec& spec) {
  SkyPreviewSpec preview;
  preview.width = spec.size.at(0);
  preview.height = spec.size.at(1);
  preview.camera_altitude_m =
      option_double(spec, "camera_altitude_km", preview.camera_altitude_m * 1e-3) * 1e3;
  return preview;
}

Texture bake_preview(const Scene& scene, const OutputSpec& spec, const ProductInputs& in,
                     const BakeContext& ctx) {
  return bake_sky_preview(scene.atmosphere, *in.at("transmittance"), *in.at("multiscattering"),
                          preview_spec(spec), ctx);
}

// A spectral scene's preview: the panels' radiance per wavelength group,
// summed, then exposed and tone mapped once (pipeline/spectral_bake.hpp).
Texture bake_preview_radiance(const Scene& scene, const OutputSpec& spec, const ProductInputs& in,
                              const BakeContext& ctx) {
  return render_sky_preview_radiance(scene.atmosphere, *in.at("transmittance"),
                                     *in.at("multiscattering"), preview_spec(spec), ctx);
}

}  // namespace

ProductInfo atmosphere_lut_product(std::string name, std::string summary,
                                   std::vector<std::string> axes, std::vector<int> size,
                                   std::vector<int> max_size, std::vector<std::string> dependencies,
                                   BakeFn bake, double ns_per_texel) {
  ProductInfo p =
      basic_product(std::move(name), std::move(summary), std::move(axes), std::move(size),
                    std::move(max_size), std::move(bake), ns_per_texel);
  p.default_formats = {"exr", "dds"};
  p.allowed_formats = {"exr", "dds", "ktx2", "png"};
  p.dependencies = std::move(dependencies);
  p.scene_sections = kAtmosphereSections;
  // Texture axes: the product's size axes, the 4D table's packed in 3.
  p.sampling.wrap.assign(std::min<size_t>(p.axes.size(), 3), "clamp");
  p.atmosphere_table = true;
  p.reads_mie_phase = true;
  // Float32 tables: zip saves 12-23% of the bytes for a third more CPU on
  // Earth's Hillaire set (docs/decisions/exr-compression.md).
  p.default_exr_compression = "none";
  return p;
}

// The iteration holds seven tables of the field's shape (RGB float32) at its
// peak, besides the field it returns: 4 Mi texels keep it near 400 MB.
constexpr double kMaxConvergedTexels = 4.0 * 1024 * 1024;

std::vector<ProductProblem> converged_field_problems(const OutputSpec& spec) {
  BrunetonSpec b = converged_multiscattering_spec(spec).bruneton;
  b.mu_s_min = -0.5;  // replaced at bake time by converged_mu_s_min, always in (-1, 0]
  try {
    check_bruneton_spec(b);
  } catch (const Error& e) {
    return {{"/scattering_shape", e.what()}};
  }
  const double texels = double(b.r_size) * b.mu_size * b.mu_s_size * b.nu_size;
  if (texels > kMaxConvergedTexels)
    return {{"/scattering_shape",
             fmt::format("expected at most {} texels in the 4D table, got {}x{}x{}x{} = {:.0f}",
                         kMaxConvergedTexels, b.r_size, b.mu_size, b.mu_s_size, b.nu_size,
                         texels)}};
  return {};
}

namespace {

// The view-dependent source (docs/reference.md "Psi_ms by view") is the
// converged model's, in skybake's layout; its slice counts need it. (No
// schema defaults: the keys are there only when the preset sets them.)
std::vector<ProductProblem> angular_multiscattering_problems(const OutputSpec& spec) {
  const bool angular = multiscattering_is_angular(spec);
  if (angular && !multiscattering_is_converged(spec))
    return {{"/angular", "applies to model \"converged\" only (its source per view comes from "
                         "the converged iteration)"}};
  if (angular && output_convention(spec) != TableConvention::skybake)
    return {{"/angular", "applies to convention \"skybake\" only (Hillaire's demo reads one "
                         "isotropic layer)"}};
  for (const char* key : {"nu_slices", "zenith_slices"})
    if (!angular && spec.options.contains(key))
      return {{std::string("/") + key, "applies to angular \"nu_zenith\" only"}};
  return {};
}

// The converged model's 4D iteration must be one bake_bruneton accepts; the
// direction rule belongs to the hillaire2020 integral, which it does not run.
std::vector<ProductProblem> converged_multiscattering_problems(const OutputSpec& spec) {
  // (The options carry the schema's defaults, so only a rule other than the default is refused.)
  if (multiscattering_is_converged(spec) &&
      spec.options.value("direction_quadrature", std::string("fibonacci")) != "fibonacci")
    return {{"/direction_quadrature",
             "applies to model \"hillaire2020\" only (model \"converged\" integrates no "
             "directions of its own)"}};
  // (No schema default: the key is there only when the preset sets it.)
  if (!multiscattering_is_converged(spec) && spec.options.contains("estimator"))
    return {{"/estimator",
             "applies to model \"converged\" only (model \"hillaire2020\" computes its "
             "Psi_ms from L_2nd and f_ms)"}};
  if (auto p = angular_multiscattering_problems(spec); !p.empty()) return p;
  if (!multiscattering_is_converged(spec) && !skyview_uses_multiple4d(spec)) return {};
  return converged_field_problems(spec);
}

ProductInfo atmosphere_product(std::string name, std::string summary, std::vector<std::string> axes,
                               std::vector<int> size, std::vector<int> max_size,
                               std::vector<std::string> dependencies, BakeFn bake,
                               double ns_per_texel, MeasureFn measure) {
  ProductInfo p = atmosphere_lut_product(std::move(name), std::move(summary), std::move(axes),
                                         std::move(size), std::move(max_size),
                                         std::move(dependencies), std::move(bake), ns_per_texel);
  p.measure_error = std::move(measure);
  return p;
}

}  // namespace

void add_atmosphere_products(std::vector<ProductInfo>& r) {
  r.push_back(atmosphere_product(
      "transmittance", "transmittance to the top of the atmosphere, (mu, r), Hillaire 2020 5.2",
      {"mu", "r"}, {256, 64}, {4096, 4096}, {}, bake_transmittance, 2700.0,
      measure_transmittance_error));
  r.back().reads_mie_phase = false;
  ProductInfo ms = atmosphere_product(
      "multiscattering",
      "multiple-scattering transfer Psi_ms, (sun zenith, altitude), Hillaire 2020 5.5",
      {"mu_s", "h"}, {32, 32}, {1024, 1024}, {"transmittance"}, bake_multiscattering, 32000.0,
      measure_multiscattering_error);
  ms.check = converged_multiscattering_problems;
  // The source by view (angular) is a volume: its view slices along w.
  ms.sampling.wrap = {"clamp", "clamp", "clamp"};
  ms.reads_mie_phase = false;  // isotropic (Hillaire 2020 eq. 7); "converged" records it
  r.push_back(std::move(ms));
  ProductInfo skyview = atmosphere_product(
      "skyview", "sky-view lat/long LUT, one layer per (altitude, sun zenith), Hillaire 2020 5.3",
      {"azimuth", "latitude"}, {192, 108}, {4096, 4096}, {"transmittance", "multiscattering"},
      bake_skyview, 400.0 * 8, measure_skyview_error);
  skyview.check = converged_multiscattering_problems;
  skyview.sampling.wrap = {"repeat", "clamp"};  // u is the azimuth, all the way round
  r.push_back(std::move(skyview));
  ProductInfo ap = atmosphere_product(
      "aerial_perspective",
      "camera froxels: RGB in-scattering, A mean transmittance, Hillaire 2020 5.4",
      {"x", "y", "slice"}, {32, 32, 32}, {512, 512, 512}, {"transmittance", "multiscattering"},
      bake_aerial_perspective, 150.0, measure_aerial_perspective_error);
  ap.allowed_formats.push_back("vdb");
  r.push_back(std::move(ap));
  ProductInfo preview = atmosphere_product(
      "sky_preview",
      "PNG previews of the sky rendered from the LUTs (sun high to below the horizon, space)",
      {"width", "height"}, {320, 180}, {2048, 2048}, {"transmittance", "multiscattering"},
      bake_preview, 30000.0, nullptr);
  preview.default_formats = {"png"};
  preview.allowed_formats = {"png", "exr"};
  preview.spectral_group_bake = bake_preview_radiance;
  preview.finish_spectral_sum = [](Texture radiance, const Scene& scene, const OutputSpec& spec) {
    return tone_map_sky_preview(radiance, scene.atmosphere, preview_spec(spec));
  };
  r.push_back(std::move(preview));
}

}  // namespace skybake

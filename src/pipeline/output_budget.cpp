#include "pipeline/output_budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "atmosphere/sh_l2.hpp"
#include "atmosphere/sky_preview.hpp"
#include "core/cube_map.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {

namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

// The most cloud types a clouds section can hold: the four of Frostbite's
// texture and 60 extra (schemas/clouds.schema.json).
constexpr std::uint64_t kMaxCloudTypes = 64;

// Per format, measured on Release builds with 2 threads, one format at a
// time; KTX2 takes DDS's factor (the same mip chain and one level's
// encoding buffer at a time) (docs/decisions/output-budgets.md has the sizes and
// resident sets). Products whose texture is small next to what they read
// (irradiance, gathering_sum, single_mie, the cloud columns) keep the
// minimum; their dependencies are budgeted as outputs of their own or are at
// default sizes.
const std::map<std::string, ProductLimits>& limits_table() {
  static const std::map<std::string, ProductLimits> table = {
      {"transmittance", {{2, 2}, {{"exr", 1.0}, {"dds", 3.5}, {"ktx2", 3.5}, {"png", 2.0}}}},
      {"multiscattering", {{2, 2}, {{"exr", 1.0}, {"dds", 3.5}, {"ktx2", 3.5}, {"png", 1.5}}}},
      {"skyview", {{1, 2}, {{"exr", 1.0}, {"dds", 2.5}, {"ktx2", 2.5}, {"png", 1.5}}}},
      {"aerial_perspective",
       {{}, {{"exr", 6.0}, {"dds", 6.0}, {"ktx2", 6.0}, {"vdb", 7.5}, {"png", 6.0}}}},
      {"sky_preview", {{}, {{"exr", 1.5}, {"png", 2.0}}}},
      {"scattering", {{}, {{"exr", 7.0}, {"dds", 7.0}, {"ktx2", 7.0}, {"png", 7.0}}}},
      {"single_mie", {}},
      {"irradiance", {{2, 2}, {}}},
      {"sky_irradiance", {{2, 2}, {}}},
      {"sky_environment", {}},
      {"scattering3d", {{}, {{"exr", 4.0}, {"dds", 6.0}, {"ktx2", 6.0}, {"png", 4.5}}}},
      {"gathering_sum", {}},
      {"noise_shape",
       {{}, {{"exr", 2.5}, {"dds", 3.0}, {"ktx2", 3.0}, {"vdb", 4.0}, {"png", 2.0}}}},
      {"noise_detail",
       {{}, {{"exr", 2.0}, {"dds", 2.5}, {"ktx2", 2.5}, {"vdb", 3.0}, {"png", 1.5}}}},
      {"curl", {{}, {{"exr", 1.0}, {"dds", 2.5}, {"ktx2", 2.5}, {"vdb", 10.5}, {"png", 8.0}}}},
      {"weather", {{2, 2}, {{"exr", 2.0}, {"dds", 2.5}, {"ktx2", 2.5}, {"png", 8.0}}}},
      {"cloud_types", {}},
      {"height_gradients", {}},
      {"cirrus", {{2, 2}, {{"exr", 2.0}, {"dds", 2.5}, {"ktx2", 2.5}, {"png", 8.0}}}},
  };
  return table;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > kSaturated / a) return kSaturated;
  return a * b;
}

}  // namespace

const ProductLimits& product_limits(const std::string& product) {
  static const ProductLimits defaults;
  const auto& table = limits_table();
  const auto it = table.find(product);
  return it == table.end() ? defaults : it->second;
}

int output_layers(const OutputSpec& spec) {
  if (spec.product == "skyview") return int(skyview_spec(spec).views.size());
  if (spec.product == "sky_preview") return int(SkyPreviewSpec().panels.size());
  if (spec.product == "sky_irradiance") return kShSymmetricCount;
  if (spec.product == "sky_environment")
    return kCubeFaces * int(sky_environment_spec(spec).views.size());
  return 1;
}

int output_channels(const OutputSpec& spec) {
  const std::string& p = spec.product;
  if (p == "scattering" || p == "scattering3d")
    return option_string(spec, "mie", "alpha") == "alpha" ? 4 : 3;
  if (p == "noise_shape") return option_string(spec, "pack", "none") != "none" ? 1 : 4;
  if (p == "noise_detail") return option_string(spec, "pack", "none") != "none" ? 1 : 3;
  if (p == "weather") return option_string(spec, "layout", "schneider") == "frostbite" ? 2 : 3;
  if (p == "cloud_types") return 2;
  if (p == "curl") return option_string(spec, "channels", "rgb") == "rg" ? 2 : 3;
  if (p == "aerial_perspective" || p == "height_gradients") return 4;
  if (limits_table().count(p)) return 3;
  return 4;
}

std::uint64_t output_texels(const OutputSpec& spec) {
  std::uint64_t texels = 1;
  for (int s : spec.size) texels = saturating_mul(texels, s > 0 ? std::uint64_t(s) : 0);
  texels = saturating_mul(texels, std::uint64_t(std::max(1, output_layers(spec))));
  if (spec.product == "cloud_types")
    texels = saturating_mul(
        texels, saturating_mul(kMaxCloudTypes, std::uint64_t(option_int(spec, "type_width", 1))));
  return texels;
}

std::uint64_t output_texture_bytes(const OutputSpec& spec) {
  return saturating_mul(output_texels(spec), 4 * sizeof(float));
}

double working_factor(const OutputSpec& spec) {
  const std::map<std::string, double>& working = product_limits(spec.product).working;
  if (working.empty()) return kMinWorkingFactor;
  double cheapest = working.begin()->second;
  for (const auto& [format, factor] : working) cheapest = std::min(cheapest, factor);
  double factor = cheapest;
  for (const std::string& format : spec.formats) {
    const auto it = working.find(format);
    if (it != working.end()) factor += it->second - cheapest;
  }
  return std::max(factor, kMinWorkingFactor);
}

std::uint64_t output_peak_bytes(const OutputSpec& spec) {
  const double peak = std::ceil(double(output_texture_bytes(spec)) * working_factor(spec));
  return peak >= double(kSaturated) ? kSaturated : std::uint64_t(peak);
}

}  // namespace skybake

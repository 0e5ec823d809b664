#include "pipeline/table_conventions.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "atmosphere/hillaire_demo_march_fit.hpp"
#include "atmosphere/transmittance_lut.hpp"

namespace skybake {

namespace {

const std::vector<std::string> kConventionProducts = {"transmittance", "multiscattering",
                                                      "skyview", "aerial_perspective"};

// His AP_SLICE_COUNT x AP_KM_PER_SLICE (RenderSkyRayMarching.hlsl).
constexpr double kDemoAerialRangeKm = kDemoAerialSize * kDemoAerialSliceM * 1e-3;

std::string size_text(const std::vector<int>& size) {
  std::string s;
  for (size_t i = 0; i < size.size(); ++i) s += (i ? "x" : "") + std::to_string(size[i]);
  return s;
}

}  // namespace

TableConvention output_convention(const OutputSpec& spec) {
  auto it = spec.options.find("convention");
  if (it == spec.options.end() || !it->is_string()) return TableConvention::skybake;
  // A name the product's schema refuses is reported there with its pointer;
  // the checks that still run on such an output (its budget, its files)
  // read it as skybake's layout rather than failing inside.
  return find_table_convention(it->get<std::string>()).value_or(TableConvention::skybake);
}

bool takes_convention(const std::string& product) {
  return std::find(kConventionProducts.begin(), kConventionProducts.end(), product) !=
         kConventionProducts.end();
}

void apply_scene_convention(const nlohmann::json& scene_doc, nlohmann::json& out) {
  if (!out.is_object() || !out.contains("product") || !out["product"].is_string()) return;
  const std::string product = out["product"].get<std::string>();
  if (!takes_convention(product)) return;
  if (!out.contains("convention") && scene_doc.contains("convention"))
    out["convention"] = scene_doc["convention"];
  if (product == "aerial_perspective" && out.value("convention", std::string()) ==
                                             "hillaire_demo" &&
      !out.contains("depth_range_km"))
    out["depth_range_km"] = kDemoAerialRangeKm;
}

void normalize_convention(OutputSpec& spec) {
  if (spec.options.value("convention", std::string()) == "skybake")
    spec.options.erase("convention");
  if (auto it = spec.options.find("fit_demo_march"); it != spec.options.end() && *it == false)
    spec.options.erase(it);
}

std::vector<ProductProblem> convention_problems(const OutputSpec& spec) {
  if (output_convention(spec) != TableConvention::hillaire_demo) {
    if (fits_demo_march(spec))
      return {{"/fit_demo_march", "fits Psi_ms to Hillaire's demo march, which reads the "
                                  "\"hillaire_demo\" convention: set \"convention\": "
                                  "\"hillaire_demo\" on the output or the scene"}};
    return {};
  }
  std::vector<ProductProblem> problems;
  const char* demo = "the \"hillaire_demo\" convention (the output's or the scene's)";
  if (spec.product == "multiscattering") {
    // GetMultipleScattering reads both axes linearly with one resolution.
    for (const char* key : {"sun_mapping", "altitude_mapping"})
      if (spec.options.value(key, std::string("linear")) != "linear")
        problems.push_back({fmt::format("/{}", key),
                            fmt::format("{} reads this axis linearly (Hillaire's demo "
                                        "GetMultipleScattering): expected \"linear\", got \"{}\"",
                                        demo, spec.options[key].get<std::string>())});
    if (spec.size.size() == 2 && spec.size[0] != spec.size[1])
      problems.push_back({"/size", fmt::format("{} reads both axes with one resolution "
                                               "(MultiScatteringLUTRes): expected a square size, "
                                               "got {}",
                                               demo, size_text(spec.size))});
  }
  if (spec.product == "skyview" &&
      spec.size != std::vector<int>{kDemoSkyviewWidth, kDemoSkyviewHeight})
    problems.push_back({"/size", fmt::format("{} reads the sky-view at the 192x108 its "
                                             "SkyViewLutParamsToUv hard-codes: expected "
                                             "[192, 108], got {}",
                                             demo, size_text(spec.size))});
  if (spec.product == "aerial_perspective" && spec.size.size() == 3 &&
      spec.size[2] != kDemoAerialSize)
    problems.push_back({"/size/2", fmt::format("{} reads {} slices (AP_SLICE_COUNT): expected "
                                               "{}, got {}",
                                               demo, kDemoAerialSize, kDemoAerialSize,
                                               spec.size[2])});
  if (spec.options.contains("max_error"))
    problems.push_back({"/max_error", fmt::format("{}: the bake measures the error of tables in "
                                                  "skybake's layout only, so max_error has "
                                                  "nothing to limit",
                                                  demo)});
  return problems;
}

OutputSpec skybake_layout_twin(const OutputSpec& spec) {
  OutputSpec twin = spec;
  twin.options.erase("convention");
  twin.options.erase("fit_demo_march");
  return twin;
}

bool fits_demo_march(const OutputSpec& spec) {
  return spec.product == "multiscattering" && spec.options.value("fit_demo_march", false);
}

void fit_to_demo_march(const Atmosphere& atm, const Texture& transmittance,
                       Texture& multiscattering) {
  TransmittanceLutSpec ts;
  ts.width = transmittance.width;
  ts.height = transmittance.height;
  ts.convention = TableConvention::hillaire_demo;
  const Texture t_demo = bake_transmittance_lut(atm, ts, BakeContext{});
  apply_demo_march_fit(atm, fit_demo_march(atm, t_demo, multiscattering), multiscattering);
}

}  // namespace skybake

// What load_scene knows of an output before anything is allocated (its
// channels, layers and texels, the smallest sizes its baker takes, its peak
// memory) against what a bake really makes, and the refusals that follow.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "pipeline/bake.hpp"
#include "pipeline/output_budget.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

const json kAtmosphere = {
    {"top_radius_km", 6460},
    {"rayleigh",
     {{"scattering_per_m", {5.802e-06, 1.3558e-05, 3.31e-05}},
      {"density", {{"exponential", {{"scale_height_km", 8}}}}}}}};

json scene_with(const json& outputs) {
  return {{"name", "budget"},
          {"planet", {{"radius_km", 6360}}},
          {"atmosphere", kAtmosphere},
          {"clouds", test::source_path("presets/clouds/storm.json").string()},
          {"outputs", outputs}};
}

fs::path write_scene(const fs::path& dir, const std::string& name, const json& scene) {
  const fs::path file = dir / name;
  std::ofstream(file) << scene.dump(2);
  return file;
}

PresetError refusal(const json& scene, const std::string& tag) {
  const fs::path file = write_scene(test::fresh_dir("budget_" + tag), "scene.json", scene);
  try {
    load_scene(file);
  } catch (const PresetError& e) {
    return e;
  }
  ADD_FAILURE() << tag << ": accepted";
  return PresetError("", "", "");
}

// Bakes `outputs` at small sizes and compares each written texture with what
// output_channels / output_layers / output_texels predicted from its spec.
void expect_predictions_match_a_bake(const json& outputs, const std::string& tag) {
  const fs::path dir = test::fresh_dir("budget_bake_" + tag);
  const Scene scene = load_scene(write_scene(dir, "scene.json", scene_with(outputs)));
  BakeOptions options;
  options.out_dir = dir / "out";
  const BakeSummary summary = bake_scene(scene, options);
  ASSERT_EQ(summary.outputs.size(), scene.outputs.size());
  for (const OutputRecord& r : summary.outputs) {
    const OutputSpec* spec = scene.find_output(r.product);
    ASSERT_TRUE(spec) << r.product;
    const ManifestEntry& e = r.entry;
    EXPECT_EQ(output_channels(*spec), int(e.channels.size())) << tag << ": " << r.product;
    EXPECT_EQ(output_layers(*spec), e.layers) << tag << ": " << r.product;
    std::uint64_t texels = std::uint64_t(e.layers);
    for (int d : e.dimensions) texels *= std::uint64_t(d);
    if (r.product == "cloud_types") {  // budgeted for the most types a section can hold
      EXPECT_GE(output_texels(*spec), texels) << tag << ": " << r.product;
    } else if (r.product != "single_mie" && r.product != "gathering_sum") {  // sizes follow another
      EXPECT_EQ(output_texels(*spec), texels) << tag << ": " << r.product;
    }
  }
}

TEST(OutputBudget, EveryProductHasLimitsForItsFormats) {
  for (const ProductInfo& p : product_registry()) {
    const ProductLimits& limits = product_limits(p.name);
    EXPECT_NE(&limits, &product_limits("no such product")) << p.name << " has no entry";
    EXPECT_LE(limits.min_size.size(), p.axes.size()) << p.name;
    for (const auto& [format, factor] : limits.working) {
      EXPECT_NE(std::find(p.allowed_formats.begin(), p.allowed_formats.end(), format),
                p.allowed_formats.end())
          << p.name << ": " << format;
      EXPECT_GE(factor, 1.0) << p.name << ": " << format;
    }
    if (!limits.working.empty()) {
      for (const std::string& format : p.allowed_formats)
        EXPECT_TRUE(limits.working.count(format)) << p.name << " has no factor for " << format;
    }
  }
}

TEST(OutputBudget, EachFormatAddsWhatItCostsBeyondTheCheapest) {
  OutputSpec curl;
  curl.product = "curl";
  curl.formats = {"exr"};
  EXPECT_EQ(working_factor(curl), 2.0) << "the minimum";
  curl.formats = {"dds"};
  EXPECT_EQ(working_factor(curl), 2.5);
  curl.formats = {"dds", "png"};
  EXPECT_EQ(working_factor(curl), 1.0 + 1.5 + 7.0);
  curl.formats = {"dds", "exr", "vdb", "png"};
  EXPECT_EQ(working_factor(curl), 1.0 + 1.5 + 0.0 + 9.5 + 7.0);
  OutputSpec other;
  other.product = "irradiance";
  other.formats = {"exr", "dds", "png"};
  EXPECT_EQ(working_factor(other), kMinWorkingFactor);
}

TEST(OutputBudget, PredictionsMatchWhatTheBakeMakesAtTheSmallestSizes) {
  expect_predictions_match_a_bake(
      {{{"product", "transmittance"}, {"size", {2, 2}}},
       {{"product", "multiscattering"}, {"size", {2, 2}}},
       {{"product", "skyview"}, {"size", {1, 2}}},
       {{"product", "aerial_perspective"}, {"size", {1, 1, 1}}},
       {{"product", "sky_preview"}, {"size", {1, 1}}},
       {{"product", "scattering"}, {"size", {2, 4, 2, 2}}},
       {{"product", "single_mie"}},
       {{"product", "irradiance"}, {"size", {2, 2}}},
       {{"product", "scattering3d"}, {"size", {2, 4, 2}}},
       {{"product", "gathering_sum"}},
       {{"product", "noise_shape"}, {"size", {128, 128, 128}}},
       {{"product", "noise_detail"}, {"size", {32, 32, 32}}},
       {{"product", "curl"}, {"size", {32, 32}}},
       {{"product", "weather"}, {"size", {2, 2}}},
       {{"product", "cloud_types"}, {"size", {1}}},
       {{"product", "height_gradients"}, {"size", {1}}},
       {{"product", "cirrus"}, {"size", {2, 2}}}},
      "smallest");
}

TEST(OutputBudget, PredictionsFollowTheOptionsThatChangeChannelsAndLayers) {
  json views = json::array();
  for (int i = 0; i < 3; ++i) views.push_back({{"altitude_km", 1.0}, {"sun_zenith_deg", 30 * i}});
  expect_predictions_match_a_bake(
      {{{"product", "skyview"}, {"size", {8, 4}}, {"views", views}},
       {{"product", "scattering"}, {"size", {2, 4, 2, 2}}, {"mie", "separate"}},
       {{"product", "scattering3d"}, {"size", {2, 4, 2}}, {"mie", "separate"}},
       {{"product", "noise_shape"}, {"size", {128, 128, 128}}, {"pack", "single_channel"}},
       {{"product", "noise_detail"}, {"size", {32, 32, 32}}, {"pack", "single_channel"}},
       {{"product", "weather"}, {"size", {16, 16}}, {"layout", "frostbite"}},
       {{"product", "cloud_types"}, {"size", {4}}, {"type_width", 2}}},
      "options");
}

TEST(OutputBudget, AxesBelowTheBakersSmallestAreRefusedAtTheAxis) {
  const std::vector<std::pair<std::string, json>> products = {
      {"transmittance", {8, 8}}, {"multiscattering", {8, 8}}, {"skyview", {8, 8}},
      {"irradiance", {8, 8}},    {"weather", {8, 8}},         {"cirrus", {8, 8}}};
  for (const auto& [product, size] : products) {
    const std::vector<int>& min = product_limits(product).min_size;
    for (size_t axis = 0; axis < min.size(); ++axis) {
      if (min[axis] < 2) continue;
      json s = size;
      s[axis] = 1;
      const PresetError e = refusal(scene_with({{{"product", product}, {"size", s}}}),
                                    product + std::to_string(axis));
      EXPECT_EQ(e.pointer(), "/outputs/0/size/" + std::to_string(axis)) << product;
      EXPECT_NE(e.rule().find("must be >= 2 (smallest " + product + " axis"), std::string::npos)
          << e.rule();
    }
  }
}

TEST(OutputBudget, SkyviewLayersCountAgainstTheOutputBudget) {
  json views = json::array();
  for (int i = 0; i < 256; ++i) views.push_back({{"altitude_km", 0.2}, {"sun_zenith_deg", 0.5 * i}});
  const PresetError e = refusal(
      scene_with({{{"product", "skyview"}, {"size", {4096, 4096}}, {"views", views}}}), "views");
  EXPECT_EQ(e.pointer(), "/outputs/0/size");
  EXPECT_NE(e.rule().find("4096x4096 texels x 256 layers (one per view) need 64.0 GiB"),
            std::string::npos)
      << e.rule();
  EXPECT_NE(e.rule().find("over the 2 GiB budget of one output"), std::string::npos);
}

TEST(OutputBudget, WorkingMemoryCountsAgainstTheBakeBudget) {
  const PresetError e =
      refusal(scene_with({{{"product", "weather"}, {"size", {8192, 8192}}}}), "weather");
  EXPECT_EQ(e.pointer(), "/outputs/0/size");
  EXPECT_NE(e.rule().find("and writing dds, exr, png takes about 8.5 GiB of memory"),
            std::string::npos)
      << e.rule();
  EXPECT_NE(e.rule().find("over the 8 GiB budget of a bake"), std::string::npos) << e.rule();
  // The same texture without its preview bakes.
  const fs::path dir = test::fresh_dir("budget_weather_dds");
  EXPECT_NO_THROW(load_scene(write_scene(
      dir, "scene.json",
      scene_with({{{"product", "weather"}, {"size", {8192, 8192}}, {"formats", {"dds"}}}}))));

  OutputSpec volume;
  volume.product = "noise_shape";
  volume.size = {512, 512, 512};
  volume.formats = {"dds", "png"};
  EXPECT_EQ(output_texture_bytes(volume), kMaxOutputBytes) << "the largest volume of the budget";
  EXPECT_LE(output_peak_bytes(volume), kMaxBakeBytes) << "still bakes";
}

TEST(OutputBudget, TexturesOfAScenePlusItsLargestBakeCountTogether) {
  const PresetError e =
      refusal(scene_with({{{"product", "noise_shape"}, {"size", {512, 512, 512}},
                           {"formats", {"dds", "exr"}}},
                          {{"product", "noise_detail"}, {"size", {512, 512, 512}}}}),
              "scene");
  EXPECT_EQ(e.pointer(), "/outputs");
  EXPECT_NE(e.rule().find("take 4.0 GiB together"), std::string::npos) << e.rule();
  EXPECT_NE(e.rule().find("baking /outputs/0 takes"), std::string::npos) << e.rule();
}

TEST(OutputBudget, SaturatesInsteadOfOverflowing) {
  OutputSpec huge;
  huge.product = "scattering";
  huge.size = {1 << 30, 1 << 30, 1 << 30, 1 << 30};
  EXPECT_EQ(output_texels(huge), UINT64_MAX);
  EXPECT_EQ(output_texture_bytes(huge), UINT64_MAX);
  EXPECT_EQ(output_peak_bytes(huge), UINT64_MAX);
}

}  // namespace
}  // namespace skybake

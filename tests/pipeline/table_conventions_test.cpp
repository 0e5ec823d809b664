// The "convention" key (pipeline/table_conventions.hpp): the scene's default
// reaches the Hillaire-family outputs only, an output's own key wins,
// skybake's layout named or not is the same output, and hillaire_demo's
// aerial perspective covers his 128 km unless the preset says otherwise.
#include "pipeline/table_conventions.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

Scene load_text(const std::string& outputs, const std::string& scene_convention) {
  const std::filesystem::path dir = test::test_dir("conventions");
  const std::filesystem::path file = dir / "scene.json";
  std::ofstream(file) << R"({ "name": "s", "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
    "atmosphere": ")" << test::source_path("presets/atmospheres/earth.json").string() << "\","
                      << (scene_convention.empty()
                              ? std::string()
                              : "\"convention\": \"" + scene_convention + "\",")
                      << "\"outputs\": [" << outputs << "] }";
  return load_scene(file);
}

const char* const kOutputs =
    R"({ "product": "transmittance" }, { "product": "multiscattering" },
       { "product": "skyview" }, { "product": "aerial_perspective" },
       { "product": "irradiance" }, { "product": "scattering3d" })";

TEST(TableConventions, TheScenesDefaultReachesTheHillaireFamilyOnly) {
  const Scene scene = load_text(kOutputs, "hillaire_demo");
  for (const char* p : {"transmittance", "multiscattering", "skyview", "aerial_perspective"})
    EXPECT_EQ(output_convention(*scene.find_output(p)), TableConvention::hillaire_demo) << p;
  for (const char* p : {"irradiance", "scattering3d"}) {
    EXPECT_EQ(output_convention(*scene.find_output(p)), TableConvention::skybake) << p;
    EXPECT_FALSE(scene.find_output(p)->options.contains("convention")) << p;
  }
  // His 32 slices of 4 km.
  EXPECT_DOUBLE_EQ(aerial_perspective_spec(*scene.find_output("aerial_perspective")).depth_range_m,
                   128e3);
  EXPECT_EQ(skyview_spec(*scene.find_output("skyview")).convention, TableConvention::hillaire_demo);
}

TEST(TableConventions, AnOutputsOwnKeyWinsAndAWrittenRangeStays) {
  const Scene scene = load_text(
      R"({ "product": "transmittance", "convention": "skybake" },
         { "product": "aerial_perspective", "depth_range_km": 64 })",
      "hillaire_demo");
  EXPECT_EQ(output_convention(*scene.find_output("transmittance")), TableConvention::skybake);
  const OutputSpec& ap = *scene.find_output("aerial_perspective");
  EXPECT_EQ(output_convention(ap), TableConvention::hillaire_demo);
  EXPECT_DOUBLE_EQ(aerial_perspective_spec(ap).depth_range_m, 64e3);
}

TEST(TableConventions, SkybakesLayoutNamedOrNotIsTheSameOutput) {
  const Scene plain = load_text(kOutputs, "");
  const Scene named = load_text(kOutputs, "skybake");
  const ProductGraph a = build_product_graph(plain, {});
  const ProductGraph b = build_product_graph(named, {});
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i)
    EXPECT_EQ(a.nodes[i].input_hash, b.nodes[i].input_hash) << a.nodes[i].info->name;
  // And hillaire_demo is another output.
  const ProductGraph c = build_product_graph(load_text(kOutputs, "hillaire_demo"), {});
  EXPECT_NE(a.find("transmittance")->input_hash, c.find("transmittance")->input_hash);
}

TEST(TableConventions, ASceneDefaultNoOutputTakesIsReportedAsWithoutEffect) {
  const Scene scene = load_text(R"({ "product": "irradiance" })", "hillaire_demo");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0].pointer, "/convention");
  EXPECT_TRUE(load_text(kOutputs, "hillaire_demo").warnings.empty());
}

TEST(TableConventions, TheShippedPresetForHisDemoAsksHisLayoutsOfEveryTable) {
  const Scene scene = load_scene(test::source_path("presets/earth_hillaire_demo.json"));
  ASSERT_EQ(scene.outputs.size(), 4u);
  for (const OutputSpec& o : scene.outputs)
    EXPECT_EQ(output_convention(o), TableConvention::hillaire_demo) << o.product;
  EXPECT_TRUE(multiscattering_is_converged(*scene.find_output("multiscattering")));
  EXPECT_TRUE(scene.warnings.empty());
}

}  // namespace
}  // namespace skybake

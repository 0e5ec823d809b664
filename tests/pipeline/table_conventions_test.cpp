// The "convention" key (pipeline/table_conventions.hpp): the scene's default
// reaches the Hillaire-family outputs only, an output's own key wins,
// skybake's layout named or not is the same output, hillaire_demo's
// aerial perspective covers his 128 km unless the preset says otherwise, and
// a Psi_ms fitted to his march asks for his layout, is baked with its
// factors recorded, and is not what skybake's own readers get.
#include "pipeline/table_conventions.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product.hpp"
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

TEST(TableConventions, APsiFittedToHisMarchAsksHisLayout) {
  OutputSpec spec;
  spec.product = "multiscattering";
  spec.options = {{"fit_demo_march", true}};
  const std::vector<ProductProblem> problems = convention_problems(spec);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].pointer, "/fit_demo_march");
  EXPECT_THROW(load_text(R"({ "product": "multiscattering", "fit_demo_march": true })", ""), Error);
  spec.options["convention"] = "hillaire_demo";
  EXPECT_TRUE(convention_problems(spec).empty());
  // Skybake's readers get the table in its layout, unfitted.
  const OutputSpec twin = skybake_layout_twin(spec);
  EXPECT_FALSE(fits_demo_march(twin));
  EXPECT_EQ(output_convention(twin), TableConvention::skybake);
}

TEST(TableConventions, APsiFittedToHisMarchRecordsItsFactors) {
  const Scene scene = load_text(
      R"({ "product": "multiscattering", "size": [16, 16], "directions": 16,
           "fit_demo_march": true })",
      "hillaire_demo");
  const OutputSpec& spec = *scene.find_output("multiscattering");
  ASSERT_TRUE(fits_demo_march(spec));
  const Texture t = bake_transmittance_lut(scene.atmosphere, {}, {});
  const Texture tex = find_product("multiscattering")->bake(scene, spec, {{"transmittance", &t}}, {});
  ASSERT_EQ(meta_int(tex.metadata, "demo_march_fit"), 8);
  OutputSpec plain = spec;
  plain.options.erase("fit_demo_march");
  const Texture unfitted = find_product("multiscattering")->bake(scene, plain, {{"transmittance", &t}}, {});
  // Each row is the unfitted row times its factor: one ratio per row and channel.
  for (int j = 0; j < tex.height; ++j)
    for (int c = 0; c < 3; ++c) {
      // The sun overhead (the last column) lights every row.
      const int lit = tex.width - 1;
      const double k = tex.at(lit, j, 0, 0, c) / unfitted.at(lit, j, 0, 0, c);
      EXPECT_GT(k, 0.5);
      EXPECT_LT(k, 1.5);
      for (int i = 0; i < lit; ++i) {
        if (unfitted.at(i, j, 0, 0, c) > 1e-30f) {
          EXPECT_NEAR(tex.at(i, j, 0, 0, c) / unfitted.at(i, j, 0, 0, c), k, 1e-5 * k) << i << " " << j;
        }
      }
    }
  // And it is another output than the unfitted one.
  const ProductGraph a = build_product_graph(scene, {});
  const Scene other = load_text(R"({ "product": "multiscattering", "size": [16, 16], "directions": 16 })",
                                "hillaire_demo");
  const std::string other_hash = build_product_graph(other, {}).find("multiscattering")->input_hash;
  EXPECT_NE(a.find("multiscattering")->input_hash, other_hash);
  // Off written out is the same output as no key.
  const Scene off = load_text(
      R"({ "product": "multiscattering", "size": [16, 16], "directions": 16, "fit_demo_march": false })",
      "hillaire_demo");
  EXPECT_EQ(build_product_graph(off, {}).find("multiscattering")->input_hash, other_hash);
}

}  // namespace
}  // namespace skybake

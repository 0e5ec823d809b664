// The multiscattering and sky-view options end to end: the terminator
// mapping and the quadratic altitude axis, the converged Psi_ms model and
// the sky-view with the 4D table's orders >= 2 bake through the command
// line, record what they are in the manifest with an error measurement, and
// bad option values are refused at load with the output's JSON pointer; the
// source by view bakes a volume.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

fs::path write_scene(const fs::path& dir, const nlohmann::json& multiscattering,
                     const nlohmann::json& skyview) {
  nlohmann::json scene = {
      {"name", "small"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs",
       {{{"product", "transmittance"}, {"size", {64, 16}}, {"formats", {"exr"}}},
        multiscattering, skyview}}};
  const fs::path file = dir / "small.json";
  std::ofstream(file) << scene.dump(2);
  return file;
}

nlohmann::json manifest_entry(const fs::path& out, const std::string& product) {
  const auto m = nlohmann::json::parse(test::read_file(out / "small/manifest.json"));
  for (const auto& o : m["outputs"])
    if (o["product"] == product) return o;
  return nullptr;
}

const nlohmann::json kSmallSkyview = {
    {"product", "skyview"},
    {"size", {16, 16}},
    {"formats", {"exr"}},
    {"views", {{{"altitude_km", 0.2}, {"sun_zenith_deg", 60}}}}};

TEST(MultiscatteringModels, ConvergedTerminatorAndSkyview4dBakeAndRecordThemselves) {
  const fs::path dir = test::fresh_dir("ms_models");
  nlohmann::json skyview = kSmallSkyview;
  skyview["multiple_scattering"] = "scattering4d";
  skyview["scattering_shape"] = {4, 16, 4, 2};
  skyview["tolerance"] = 0.01;
  const fs::path preset = write_scene(
      dir,
      {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}},
       {"model", "converged"}, {"sun_mapping", "terminator"}, {"altitude_mapping", "quadratic"},
       {"scattering_shape", {4, 16, 4, 2}}, {"tolerance", 0.01}, {"estimator", "mean"}},
      skyview);
  const auto r = test::run_skybake({"bake", preset.string(), "-o", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ms = manifest_entry(dir / "out", "multiscattering");
  EXPECT_EQ(ms["metadata"]["model"], "converged");
  EXPECT_EQ(ms["metadata"]["mu_s_mapping"], "terminator");
  EXPECT_EQ(ms["metadata"]["altitude_mapping"], "quadratic");
  EXPECT_EQ(ms["metadata"]["scattering_shape"], "4x16x4x2");
  EXPECT_EQ(ms["metadata"]["estimator"], "mean");
  EXPECT_TRUE(ms["error"].contains("max_rel")) << ms.dump();
  const auto sv = manifest_entry(dir / "out", "skyview");
  EXPECT_EQ(sv["metadata"]["multiple_scattering"], "scattering4d");
  EXPECT_TRUE(sv["error"].contains("max_rel")) << sv.dump();
}

TEST(MultiscatteringModels, SymmetricGaussRuleBakesAndNamesItself) {
  const fs::path dir = test::fresh_dir("ms_symmetric_gauss");
  const fs::path preset = write_scene(
      dir,
      {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}},
       {"sun_mapping", "terminator"}, {"direction_quadrature", "symmetric_gauss"},
       {"directions", 96}},
      kSmallSkyview);
  const auto r = test::run_skybake({"bake", preset.string(), "-o", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ms = manifest_entry(dir / "out", "multiscattering");
  EXPECT_EQ(ms["metadata"]["direction_set"], "symmetric_gauss");
  EXPECT_NE(ms["metadata"]["direction_rule"].get<std::string>().find("6 on [-1, mu_h(r)]"),
            std::string::npos)
      << ms["metadata"].dump();
  EXPECT_TRUE(ms["error"].contains("max_rel")) << ms.dump();
}

TEST(MultiscatteringModels, BadOptionsAreRefusedWithTheirPointer) {
  const fs::path dir = test::fresh_dir("ms_models_bad");
  const fs::path odd_mu = write_scene(dir,
                                      {{"product", "multiscattering"},
                                       {"size", {8, 8}},
                                       {"model", "converged"},
                                       {"scattering_shape", {8, 31, 8, 4}}},
                                      kSmallSkyview);
  auto r = test::run_skybake({"validate", odd_mu.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // validate: a check failed
  EXPECT_NE((r.out + r.err).find("/outputs/1/scattering_shape"), std::string::npos)
      << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("mu even"), std::string::npos) << r.out << r.err;
  const fs::path bad_model = write_scene(
      dir, {{"product", "multiscattering"}, {"size", {8, 8}}, {"model", "convergd"}},
      kSmallSkyview);
  r = test::run_skybake({"validate", bad_model.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // validate: a check failed
  EXPECT_NE((r.out + r.err).find("/outputs/1/model"), std::string::npos) << r.out << r.err;
  nlohmann::json skyview = kSmallSkyview;
  skyview["multiple_scattering"] = "bruneton";
  const fs::path bad_source =
      write_scene(dir, {{"product", "multiscattering"}, {"size", {8, 8}}}, skyview);
  r = test::run_skybake({"validate", bad_source.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // validate: a check failed
  EXPECT_NE((r.out + r.err).find("/outputs/2/multiple_scattering"), std::string::npos)
      << r.out << r.err;
  const fs::path bad_rule = write_scene(
      dir, {{"product", "multiscattering"}, {"size", {8, 8}}, {"direction_quadrature", "gauss"}},
      kSmallSkyview);
  r = test::run_skybake({"validate", bad_rule.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("/outputs/1/direction_quadrature"), std::string::npos)
      << r.out << r.err;
  const fs::path bad_altitude = write_scene(
      dir, {{"product", "multiscattering"}, {"size", {8, 8}}, {"altitude_mapping", "cubic"}},
      kSmallSkyview);
  r = test::run_skybake({"validate", bad_altitude.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("/outputs/1/altitude_mapping"), std::string::npos)
      << r.out << r.err;
  const fs::path converged_rule = write_scene(dir,
                                              {{"product", "multiscattering"},
                                               {"size", {8, 8}},
                                               {"model", "converged"},
                                               {"direction_quadrature", "symmetric_gauss"}},
                                              kSmallSkyview);
  r = test::run_skybake({"validate", converged_rule.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("/outputs/1/direction_quadrature"), std::string::npos)
      << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("hillaire2020"), std::string::npos) << r.out << r.err;
  // Any estimator, the converged model's default too: hillaire2020 has none.
  const fs::path hillaire_estimator = write_scene(
      dir, {{"product", "multiscattering"}, {"size", {8, 8}}, {"estimator", "relative"}},
      kSmallSkyview);
  r = test::run_skybake({"validate", hillaire_estimator.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("/outputs/1/estimator"), std::string::npos) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("converged"), std::string::npos) << r.out << r.err;
  const fs::path bad_estimator = write_scene(dir,
                                             {{"product", "multiscattering"},
                                              {"size", {8, 8}},
                                              {"model", "converged"},
                                              {"estimator", "median"}},
                                             kSmallSkyview);
  r = test::run_skybake({"validate", bad_estimator.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("/outputs/1/estimator"), std::string::npos) << r.out << r.err;
}

// The source by view (docs/reference.md "Psi_ms by view"): a volume of
// 1 + nu_slices + zenith_slices slices in every format, named in the
// metadata, read by the sky-view bake; the option is refused where it does
// not apply.
TEST(MultiscatteringModels, SourceByViewBakesAVolumeAndIsRefusedElsewhere) {
  const fs::path dir = test::fresh_dir("ms_by_view");
  const nlohmann::json view = {{"product", "multiscattering"}, {"size", {8, 8}},
                               {"formats", {"exr", "dds"}}, {"model", "converged"},
                               {"scattering_shape", {4, 16, 4, 2}}, {"tolerance", 0.01},
                               {"angular", "nu_zenith"}, {"nu_slices", 4}, {"zenith_slices", 3}};
  const fs::path preset = write_scene(dir, view, kSmallSkyview);
  auto r = test::run_skybake({"bake", preset.string(), "-o", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ms = manifest_entry(dir / "out", "multiscattering");
  EXPECT_EQ(ms["metadata"]["nu_slices"], 4) << ms.dump();
  EXPECT_EQ(ms["metadata"]["zenith_slices"], 3);
  EXPECT_EQ(ms["metadata"]["wrap_w"], "clamp");
  r = test::run_skybake({"info", (dir / "out/small/multiscattering.dds").string()});
  EXPECT_NE(r.out.find("8x8x8"), std::string::npos) << r.out;  // 1 + 4 + 3 slices
  EXPECT_TRUE(manifest_entry(dir / "out", "skyview")["error"].contains("max_rel"));

  const auto refused = [&](nlohmann::json ms_output, const std::string& pointer,
                           const std::string& words) {
    const fs::path file = write_scene(dir, ms_output, kSmallSkyview);
    const auto v = test::run_skybake({"validate", file.string()});
    EXPECT_EQ(v.exit_code, 1) << v.out << v.err;
    EXPECT_NE((v.out + v.err).find(pointer), std::string::npos) << v.out << v.err;
    EXPECT_NE((v.out + v.err).find(words), std::string::npos) << v.out << v.err;
  };
  nlohmann::json hillaire = view;
  hillaire.erase("model");
  refused(hillaire, "/outputs/1/angular", "converged");
  nlohmann::json demo = view;
  demo["convention"] = "hillaire_demo";
  refused(demo, "/outputs/1/angular", "skybake");
  nlohmann::json slices_alone = view;
  slices_alone.erase("angular");
  refused(slices_alone, "/outputs/1/nu_slices", "nu_zenith");
  nlohmann::json one_slice = view;
  one_slice["zenith_slices"] = 1;
  refused(one_slice, "/outputs/1/zenith_slices", "");
}

}  // namespace
}  // namespace skybake

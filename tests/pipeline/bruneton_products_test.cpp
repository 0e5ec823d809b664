// Precomputed scattering products end to end: one bake makes the
// 4D table and its irradiance, the manifest records the orders used and the
// last residual, convergence mode iterates until the tolerance, companions
// are computed from their family without being written when not requested.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "io/texture_file.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

// A small Earth scene (reduced sizes keep the test fast).
fs::path write_scene(const fs::path& dir, const nlohmann::json& scattering) {
  nlohmann::json scene = {
      {"name", "small"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.1, 0.1, 0.1}}}},
      {"atmosphere", test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs",
       {scattering,
        {{"product", "irradiance"}, {"size", {32, 8}}, {"formats", {"exr"}}},
        {{"product", "scattering3d"}, {"size", {8, 32, 8}}, {"formats", {"exr", "dds"}},
         {"orders", 3}},
        {{"product", "gathering_sum"}, {"formats", {"exr"}}}}}};
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

TEST(BrunetonProducts, FixedOrdersAreRecordedAndFilesReadBack) {
  const fs::path dir = test::fresh_dir("bruneton_fixed");
  const fs::path preset =
      write_scene(dir, {{"product", "scattering"}, {"size", {8, 32, 8, 4}}, {"orders", 3},
                        {"formats", {"exr", "dds"}}});
  const auto r = test::run_skybake({"bake", preset.string(), "-o", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = manifest_entry(dir / "out", "scattering");
  EXPECT_EQ(s["dimensions"], nlohmann::json::array({32, 32, 8})) << "nu*mu_s x mu x r";
  EXPECT_EQ(s["channels"].size(), 4u) << "Mie red in alpha by default";
  EXPECT_EQ(s["metadata"]["orders"], 3);
  EXPECT_TRUE(s["metadata"].contains("last_residual"));
  const auto irr = manifest_entry(dir / "out", "irradiance");
  EXPECT_EQ(irr["dimensions"], nlohmann::json::array({32, 8}));
  EXPECT_EQ(irr["metadata"]["orders"], 3) << "irradiance comes from the same bake";
  const Texture t = read_texture_file((dir / "out/small/scattering.dds").string()).texture;
  EXPECT_EQ(t.depth, 8);
  for (float v : t.data) ASSERT_GE(v, 0.0f);
}

TEST(BrunetonProducts, ConvergenceModeRecordsOrdersAndResidual) {
  const fs::path dir = test::fresh_dir("bruneton_converge");
  const fs::path preset = write_scene(
      dir, {{"product", "scattering"}, {"size", {8, 32, 8, 4}}, {"tolerance", 0.01},
            {"max_orders", 30}, {"formats", {"exr"}}});
  const auto r = test::run_skybake({"bake", preset.string(), "-o", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = manifest_entry(dir / "out", "scattering");
  const int orders = s["metadata"]["orders"].get<int>();
  const double residual = s["metadata"]["last_residual"].get<double>();
  EXPECT_GT(orders, 2);
  EXPECT_LT(orders, 30);
  EXPECT_LT(residual, 0.01);
}

TEST(BrunetonProducts, CompanionAloneComputesItsFamilyInMemory) {
  const fs::path dir = test::fresh_dir("bruneton_only");
  const fs::path preset =
      write_scene(dir, {{"product", "scattering"}, {"size", {8, 32, 8, 4}}, {"orders", 2},
                        {"formats", {"exr"}}});
  const auto r = test::run_skybake(
      {"bake", preset.string(), "-o", (dir / "out").string(), "--only", "irradiance", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out/small/irradiance.exr"));
  EXPECT_FALSE(fs::exists(dir / "out/small/scattering.exr"));
}

}  // namespace
}  // namespace skybake

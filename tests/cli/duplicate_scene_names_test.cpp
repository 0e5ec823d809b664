// Two scene presets of one name in one run would bake into one folder, the
// later overwriting the earlier's manifest entries: every command that takes
// several scenes refuses them as an invalid preset (exit 3 for bake, plan
// and report; a failed check, exit 1, for validate), naming both files.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using skybake::test::run_skybake;

namespace {

void write_scene(const fs::path& file, const std::string& name, int width) {
  const nlohmann::json scene = {
      {"name", name},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", skybake::test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs", {{{"product", "transmittance"}, {"size", {width, 16}}, {"formats", {"exr"}}}}}};
  std::ofstream(file) << scene.dump(2);
}

TEST(DuplicateSceneNames, AreRefusedAtLoadNamingBothFiles) {
  const fs::path dir = skybake::test::test_dir("cli_duplicate_names");
  const fs::path a = dir / "a.json", b = dir / "b.json", out = dir / "out";
  write_scene(a, "twin", 32);
  write_scene(b, "twin", 64);
  const std::string rule = b.string() + ": /name: 'twin' is also the name of the scene " +
                           a.string() + "; two scenes of one name would bake into one folder";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bake", a.string(), b.string(), "-o", out.string()},
        {"bake", dir.string(), "-o", out.string()},
        {"plan", a.string(), b.string(), "-o", out.string()},
        {"report", a.string(), b.string(), "-o", (dir / "report").string()}}) {
    SCOPED_TRACE(args[0] + " " + args[1]);
    const auto r = run_skybake(args);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_THAT(r.err, HasSubstr(rule));
  }
  EXPECT_FALSE(fs::exists(out / "twin")) << "refused before anything is baked";
  const auto v = run_skybake({"validate", a.string(), b.string()});
  EXPECT_EQ(v.exit_code, 1) << v.err;
  EXPECT_THAT(v.err, HasSubstr(rule));
}

TEST(DuplicateSceneNames, OneFileNamedTwiceIsOneScene) {
  const fs::path dir = skybake::test::test_dir("cli_duplicate_file");
  const fs::path a = dir / "a.json";
  write_scene(a, "single", 32);
  const auto r = run_skybake({"bake", a.string(), (dir / "." / "a.json").string(), "-o",
                              (dir / "out").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["scenes"].size(), 1u);
}

}  // namespace

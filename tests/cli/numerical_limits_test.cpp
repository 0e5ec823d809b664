// Presets that pass every check yet sit past what a baker computes: the
// schema refuses the values whose breakdown is known (a subnormal scale
// height, |g| within 1e-6 of 1: tests/bad_presets/), and a baker that still
// returns a NaN or an infinity fails the bake as a preset problem (exit 3)
// naming the preset and the output, never as a file error (exit 4).
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using skybake::test::read_file;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

// presets/extreme/rayleigh_1_per_m.json with one small sky-view whose orders
// >= 2 come from the 4D iteration: vertical optical depth 8000, where that
// path returns NaN at the first texel.
fs::path opaque_scattering4d_scene(const fs::path& dir) {
  nlohmann::json scene =
      nlohmann::json::parse(read_file(source_path("presets/extreme/rayleigh_1_per_m.json")));
  scene.erase("$schema");
  scene["name"] = "opaque4d";
  scene["outputs"] = {{{"product", "skyview"},
                       {"size", {16, 8}},
                       {"formats", {"exr"}},
                       {"multiple_scattering", "scattering4d"},
                       {"views", {{{"altitude_km", 0}, {"sun_zenith_deg", 0}}}}}};
  const fs::path file = dir / "opaque4d.json";
  std::ofstream(file) << scene.dump(2);
  return file;
}

TEST(NumericalLimits, ANonFiniteBakeIsAPresetProblemNotAFileError) {
  const fs::path dir = skybake::test::test_dir("cli_numerical_limits");
  const fs::path scene = opaque_scattering4d_scene(dir);
  const auto v = run_skybake({"validate", scene.string()});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  const auto r = run_skybake({"bake", scene.string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_THAT(r.err, HasSubstr(scene.string() + ": /outputs/0: skyview came out non-finite ("));
  EXPECT_THAT(r.err, HasSubstr("past what the skyview baker computes"));
  EXPECT_FALSE(fs::exists(dir / "out" / "opaque4d" / "skyview.exr"));
}

}  // namespace

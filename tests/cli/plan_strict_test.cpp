// `plan --emit ... --strict` makes every emitted task a `bake --strict`, so a
// farm that runs the plan fails the task of an output that finished with a
// warning, as a local `bake --strict` would (docs/farm.md).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

// A scene whose one output always warns: no table meets a max_error of 1e-9.
fs::path write_warning_scene(const fs::path& dir) {
  const fs::path preset = dir / "warns.json";
  std::ofstream(preset) << R"({
  "name": "warns",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" << test::source_path("presets/atmospheres/earth.json").string() << R"(",
  "outputs": [ { "product": "transmittance", "size": [32, 16], "formats": ["exr"],
                 "max_error": 1e-9 } ]
})";
  return preset;
}

// Runs dir/build.ninja as it is (output in dir/ninja.log); ninja's exit code.
int run_ninja(const fs::path& dir) {
  const fs::path build = dir / "build.ninja";
  const std::string cmd = "ninja -f '" + build.string() + "' > '" + (dir / "ninja.log").string() +
                          "' 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Emits a ninja file for the scene (with `extra` flags) and runs it; ninja's exit code.
int run_emitted_ninja(const fs::path& dir, const fs::path& preset,
                      const std::vector<std::string>& extra) {
  const fs::path out = dir / "out";
  fs::remove_all(out);
  const fs::path build = dir / "build.ninja";
  std::vector<std::string> args = {"plan", preset.string(), "-o", out.string(), "--emit", "ninja",
                                   "--emit-file", build.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto plan = test::run_skybake(args);
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
  return run_ninja(dir);
}

TEST(PlanStrict, AWarningFailsTheEmittedTaskOnlyUnderStrict) {
  const fs::path dir = test::fresh_dir("plan_strict");
  const fs::path preset = write_warning_scene(dir);
  ASSERT_EQ(std::system("ninja --version > /dev/null 2>&1"), 0) << "ninja is not installed";
  for (const std::string edges : {"scene", "product"}) {
    SCOPED_TRACE("--edges " + edges);
    EXPECT_EQ(run_emitted_ninja(dir, preset, {"--edges", edges}), 0)
        << test::read_file(dir / "ninja.log");
    EXPECT_NE(run_emitted_ninja(dir, preset, {"--edges", edges, "--strict"}), 0)
        << "the warning must fail the task: " << test::read_file(dir / "ninja.log");
    EXPECT_NE(test::read_file(dir / "ninja.log").find("error_above_limit"), std::string::npos)
        << test::read_file(dir / "ninja.log");
    // The outputs are current now; the warning, read from the manifest, still fails the task.
    EXPECT_NE(run_ninja(dir), 0) << test::read_file(dir / "ninja.log");
  }
}

TEST(PlanStrict, NeedsEmit) {
  const fs::path dir = test::fresh_dir("plan_strict_needs_emit");
  const auto r = test::run_skybake({"plan", write_warning_scene(dir).string(), "--strict"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--emit"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace skybake

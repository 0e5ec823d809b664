// The executable's surface: --version, --help of every subcommand, usage
// errors, plan and info.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using skybake::test::fresh_dir;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

TEST(Cli, VersionPrintsTheProjectVersion) {
  const auto r = run_skybake({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("skybake " SKYBAKE_VERSION), std::string::npos) << r.out;
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const std::string cmd : {"bake", "validate", "plan", "info", "check-tiling", "report"}) {
    const auto r = run_skybake({cmd, "--help"});
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd << ": " << r.out;
  }
  const auto top = run_skybake({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("transmittance"), std::string::npos) << "products listed in --help";
  EXPECT_NE(top.out.find("Examples"), std::string::npos);
}

TEST(Cli, MissingSubcommandIsAUsageError) {
  EXPECT_EQ(run_skybake({}).exit_code, 2);
  EXPECT_EQ(run_skybake({"bake"}).exit_code, 2);
  EXPECT_EQ(run_skybake({"frobnicate"}).exit_code, 2);
}

TEST(Cli, MissingPresetFileIsNamed) {
  const fs::path out = fresh_dir("cli_missing");
  const auto r = run_skybake({"bake", "no/such/preset.json", "-o", out.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("no/such/preset.json"), std::string::npos) << r.err;
  EXPECT_TRUE(skybake::test::list_files(out).empty());
}

TEST(Cli, PlanShowsProductsAndState) {
  const fs::path out = fresh_dir("cli_plan");
  const std::string earth = source_path("presets/earth.json").string();
  auto r = run_skybake({"plan", earth, "-o", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  const auto& node = j["scenes"][0]["nodes"][0];
  EXPECT_EQ(node["product"], "transmittance");
  EXPECT_FALSE(node["up_to_date"].get<bool>());
  EXPECT_EQ(node["reason"], "not baked yet");
  // plan writes nothing.
  EXPECT_TRUE(skybake::test::list_files(out).empty());

  ASSERT_EQ(run_skybake({"bake", earth, "-o", out.string(), "-q"}).exit_code, 0);
  j = nlohmann::json::parse(run_skybake({"plan", earth, "-o", out.string(), "--json"}).out);
  EXPECT_TRUE(j["scenes"][0]["nodes"][0]["up_to_date"].get<bool>());
  EXPECT_EQ(j["scenes"][0]["folder"], (out / "earth").string());
  EXPECT_EQ(j["out_dir"], out.string());
}

// -o is the output folder in plan as in bake and report; the emitted build
// file has its own flag and goes to stdout without it.
TEST(Cli, PlanEmitsIntoEmitFileForTheFolderOfDashO) {
  const fs::path dir = fresh_dir("cli_plan_emit");
  const std::string earth = source_path("presets/earth.json").string();
  const fs::path out = dir / "baked", ninja = dir / "build.ninja";
  auto r = run_skybake({"plan", earth, "-o", out.string(), "--emit", "ninja", "--emit-file",
                        ninja.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  const std::string text = skybake::test::read_file(ninja);
  EXPECT_NE(text.find("builddir = " + out.string() + "\n"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(out)) << "plan writes nothing into the output folder";

  r = run_skybake({"plan", earth, "--out", out.string(), "--emit", "ninja"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, text) << "without --emit-file the same file goes to stdout";
}

TEST(Cli, InfoReadsBackBakedFiles) {
  const fs::path out = fresh_dir("cli_info");
  const std::string earth = source_path("presets/earth.json").string();
  ASSERT_EQ(run_skybake({"bake", earth, "-o", out.string(), "-q"}).exit_code, 0);
  for (const std::string f : {"transmittance.exr", "transmittance.dds"}) {
    const auto r = run_skybake({"info", (out / "earth" / f).string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out)["files"][0];
    EXPECT_EQ(j["width"], 256) << f;
    EXPECT_EQ(j["height"], 64) << f;
    EXPECT_EQ(j["metadata"]["product"], "transmittance") << f;
    // Transmittance lies in [0, 1].
    for (const auto& c : j["channels"]) {
      EXPECT_GE(c["min"].get<double>(), 0.0);
      EXPECT_LE(c["max"].get<double>(), 1.0);
    }
  }
}

}  // namespace

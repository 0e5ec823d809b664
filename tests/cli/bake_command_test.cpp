// End-to-end tests of `skybake bake` on the shipped Earth preset: files,
// manifest, incremental re-runs, --force, --only, determinism across thread
// counts and the --json summary.
#include <gtest/gtest.h>

#include <map>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using skybake::test::fresh_dir;
using skybake::test::list_files;
using skybake::test::read_file;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

const std::string kEarth = source_path("presets/earth.json").string();

TEST(BakeCommand, EarthWritesTransmittanceAndManifest) {
  const fs::path out = fresh_dir("bake_earth");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "earth/transmittance.exr"));
  EXPECT_TRUE(fs::exists(out / "earth/transmittance.dds"));
  // No temporaries left behind.
  for (const std::string& f : list_files(out))
    EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;

  const auto manifest = nlohmann::json::parse(read_file(out / "earth/manifest.json"));
  EXPECT_EQ(manifest["scene"], "earth");
  ASSERT_EQ(manifest["outputs"].size(), 5u) << "earth.json asks for five outputs";
  nlohmann::json t;
  for (const auto& o : manifest["outputs"])
    if (o["product"] == "transmittance") t = o;
  EXPECT_EQ(t["product"], "transmittance");
  EXPECT_EQ(t["dimensions"], nlohmann::json::array({256, 64}));
  EXPECT_EQ(t["channels"], nlohmann::json::array({"R", "G", "B"}));
  EXPECT_EQ(t["files"].size(), 2u);
  EXPECT_EQ(t["input_hash"].get<std::string>().size(), 16u);
  EXPECT_TRUE(t["metadata"].contains("parameterization"));
  EXPECT_FALSE(t.contains("bake_seconds")) << "times go to bake_log.json";
  const auto log = nlohmann::json::parse(read_file(out / "earth/bake_log.json"));
  EXPECT_GE(log["outputs"]["transmittance"]["bake_seconds"].get<double>(), 0.0);
}

TEST(BakeCommand, ManifestRecordsEstimatedErrorAndTimeOfEveryLut) {
  const fs::path out = fresh_dir("bake_error_estimates");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q"}).exit_code, 0);
  const auto manifest = nlohmann::json::parse(read_file(out / "earth/manifest.json"));
  const auto log = nlohmann::json::parse(read_file(out / "earth/bake_log.json"));
  // Discretisation error bounds of the default settings against 8-16x finer
  // integrations of the same quantity (documented in the product headers).
  const std::map<std::string, double> bound = {{"transmittance", 1e-4},
                                               {"multiscattering", 0.05},
                                               {"skyview", 0.05},
                                               {"aerial_perspective", 0.01}};
  size_t checked = 0;
  for (const auto& o : manifest["outputs"]) {
    const std::string product = o["product"];
    EXPECT_GT(log["outputs"][o["name"].get<std::string>()]["bake_seconds"].get<double>(), 0.0)
        << product;
    if (!bound.count(product)) continue;
    const auto& e = o["estimated_error"];
    ASSERT_TRUE(e.is_object()) << product;
    EXPECT_GT(e["samples"].get<int>(), 0) << product;
    EXPECT_LT(e["max_rel"].get<double>(), bound.at(product)) << product;
    EXPECT_LE(e["rms_rel"].get<double>(), e["max_rel"].get<double>()) << product;
    ++checked;
  }
  EXPECT_EQ(checked, bound.size());
}

TEST(BakeCommand, SecondRunDoesNoWorkUnlessForced) {
  const fs::path out = fresh_dir("bake_incremental");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q"}).exit_code, 0);
  const auto mtime = fs::last_write_time(out / "earth/transmittance.exr");

  auto again = run_skybake({"bake", kEarth, "-o", out.string(), "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  auto summary = nlohmann::json::parse(again.out);
  EXPECT_EQ(summary["scenes"][0]["outputs"][0]["status"], "up to date");
  EXPECT_TRUE(summary["scenes"][0]["computed"].empty());
  EXPECT_EQ(fs::last_write_time(out / "earth/transmittance.exr"), mtime);

  auto forced = run_skybake({"bake", kEarth, "-o", out.string(), "--json", "--force"});
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  summary = nlohmann::json::parse(forced.out);
  EXPECT_EQ(summary["scenes"][0]["outputs"][0]["status"], "baked");
  EXPECT_EQ(summary["scenes"][0]["outputs"][0]["reason"], "forced");
}

TEST(BakeCommand, DeletedFileIsBakedAgain) {
  const fs::path out = fresh_dir("bake_deleted");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q"}).exit_code, 0);
  fs::remove(out / "earth/transmittance.dds");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["scenes"][0]["outputs"][0]["status"], "baked");
  EXPECT_NE(summary["scenes"][0]["outputs"][0]["reason"].get<std::string>().find("missing"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(out / "earth/transmittance.dds"));
}

TEST(BakeCommand, ByteIdenticalForOneAndTwoThreads) {
  const fs::path one = fresh_dir("bake_threads1"), two = fresh_dir("bake_threads2");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", one.string(), "-q", "--threads", "1"}).exit_code, 0);
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", two.string(), "-q", "--threads", "2"}).exit_code, 0);
  for (const std::string f : {"earth/transmittance.exr", "earth/transmittance.dds"}) {
    const std::string a = read_file(one / f), b = read_file(two / f);
    ASSERT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << f << " differs between 1 and 2 threads";
  }
}

TEST(BakeCommand, OnlyUnknownProductIsAUsageErrorWithSuggestion) {
  const fs::path out = fresh_dir("bake_only_unknown");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", "transmitance"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'transmittance'"), std::string::npos) << r.err;
  EXPECT_TRUE(list_files(out).empty());
}

TEST(BakeCommand, JsonSummaryListsFilesAndShape) {
  const fs::path out = fresh_dir("bake_json");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--json", "--only",
                              "transmittance"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["ok"].get<bool>());
  const auto& o = j["scenes"][0]["outputs"][0];
  EXPECT_EQ(o["product"], "transmittance");
  EXPECT_EQ(o["files"].size(), 2u);
  for (const auto& f : o["files"]) EXPECT_TRUE(fs::exists(f["path"].get<std::string>()));
}

}  // namespace

namespace {

TEST(BakeCommand, DependenciesAreComputedButWrittenOnlyWhenRequested) {
  const fs::path out = fresh_dir("bake_only_skyview");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", "skyview", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out)["scenes"][0];
  EXPECT_EQ(j["computed"], nlohmann::json::array({"transmittance", "multiscattering", "skyview"}));
  EXPECT_TRUE(fs::exists(out / "earth/skyview.exr"));
  EXPECT_FALSE(fs::exists(out / "earth/transmittance.exr"));
  EXPECT_FALSE(fs::exists(out / "earth/multiscattering.exr"));
  const auto manifest = nlohmann::json::parse(read_file(out / "earth/manifest.json"));
  ASSERT_EQ(manifest["outputs"].size(), 1u);
  EXPECT_EQ(manifest["outputs"][0]["product"], "skyview");
  EXPECT_EQ(manifest["outputs"][0]["layers"], 8);
}

TEST(BakeCommand, CurrentDependenciesAreReadFromDiskAndGiveIdenticalFiles) {
  const fs::path out = fresh_dir("bake_deps_from_disk");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q", "--only",
                         "transmittance,multiscattering,skyview"})
                .exit_code,
            0);
  const std::string before = read_file(out / "earth/skyview.dds");
  const auto r = run_skybake(
      {"bake", kEarth, "-o", out.string(), "--only", "skyview", "--force", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out)["scenes"][0];
  EXPECT_EQ(j["computed"], nlohmann::json::array({"skyview"}));
  EXPECT_EQ(j["loaded"], nlohmann::json::array({"transmittance", "multiscattering"}));
  EXPECT_TRUE(read_file(out / "earth/skyview.dds") == before)
      << "dependents must not depend on whether their inputs were baked or read back";
}

TEST(BakeCommand, EveryShippedPresetBakesFiniteFiles) {
  const fs::path out = fresh_dir("bake_shipped");
  for (const std::string p : {"presets/mars.json", "presets/tiny_planet.json"}) {
    const auto r = run_skybake({"bake", source_path(p).string(), "-o", out.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << p << ": " << r.err;
    for (const auto& o : nlohmann::json::parse(r.out)["scenes"][0]["outputs"])
      for (const auto& f : o["files"]) EXPECT_TRUE(fs::exists(f["path"].get<std::string>()));
  }
}

}  // namespace

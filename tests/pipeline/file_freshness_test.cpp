// Freshness that cannot be fooled (pipeline/freshness.hpp): the manifest
// records each file's size and content hash and holds nothing that varies
// between runs; times go to bake_log.json beside it. A truncated file, a
// file edited in place, or one edited with its time put back (caught by
// verify) is baked again.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/file_record.hpp"
#include "pipeline/bake.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using namespace skybake;

namespace {

// A small scene: transmittance (two formats) and the multi-scattering table
// that reads it.
Scene small_scene(const fs::path& dir) {
  const fs::path preset = dir / "small.json";
  const nlohmann::json earth =
      nlohmann::json::parse(test::read_file(test::source_path("presets/earth.json")));
  nlohmann::json scene = earth;
  scene["name"] = "small";
  scene["outputs"] = nlohmann::json::array(
      {{{"product", "transmittance"}, {"size", {32, 16}}, {"formats", {"exr", "dds"}}},
       {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}}}});
  scene["atmosphere"] = test::source_path("presets/atmospheres/earth.json").string();
  std::ofstream(preset) << scene.dump(2);
  return load_scene(preset);
}

std::map<std::string, std::string> statuses(const BakeSummary& s) {
  std::map<std::string, std::string> out;
  for (const OutputRecord& r : s.outputs) out[r.product] = r.status + ": " + r.reason;
  return out;
}

void overwrite_byte(const fs::path& file, size_t offset) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(offset);
  const char c = char(f.get());
  f.seekp(offset);
  f.put(char(c ^ 0x5A));
}

void set_mtime_ns(const fs::path& file, int64_t ns) {
  const timespec t{time_t(ns / 1000000000), long(ns % 1000000000)};
  const timespec times[2] = {t, t};
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0);
}

class FileFreshness : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::test_dir("freshness");
    scene_ = small_scene(dir_);
    options_.out_dir = dir_ / "out";
    first_ = bake_scene(scene_, options_);
  }
  fs::path scene_dir() const { return dir_ / "out" / "small"; }

  fs::path dir_;
  Scene scene_;
  BakeOptions options_;
  BakeSummary first_;
};

TEST_F(FileFreshness, ManifestRecordsSizeAndHashOfEveryFile) {
  const auto m = nlohmann::json::parse(test::read_file(scene_dir() / "manifest.json"));
  size_t files = 0;
  for (const auto& o : m["outputs"])
    for (const auto& f : o["files"]) {
      const fs::path p = scene_dir() / f["path"].get<std::string>();
      EXPECT_EQ(f["size"].get<uint64_t>(), fs::file_size(p)) << p;
      EXPECT_EQ(f["hash"].get<std::string>(), hash_file(p)) << p;
      ++files;
    }
  EXPECT_EQ(files, 3u);
}

TEST_F(FileFreshness, ManifestIsByteIdenticalAcrossBakesAndTimesGoToTheLog) {
  const std::string before = test::read_file(scene_dir() / "manifest.json");
  EXPECT_EQ(before.find("seconds"), std::string::npos) << "times vary between runs";
  BakeOptions force = options_;
  force.force = true;
  bake_scene(scene_, force);
  EXPECT_EQ(test::read_file(scene_dir() / "manifest.json"), before);
  const auto log = nlohmann::json::parse(test::read_file(scene_dir() / "bake_log.json"));
  EXPECT_TRUE(log["outputs"]["transmittance"]["bake_seconds"].is_number());
  EXPECT_TRUE(log["outputs"]["transmittance"]["mtime_ns"].contains("transmittance.dds"));
}

TEST_F(FileFreshness, UnchangedFilesAreCurrent) {
  const auto s = statuses(bake_scene(scene_, options_));
  EXPECT_EQ(s.at("transmittance"), "up to date: up to date");
  EXPECT_EQ(s.at("multiscattering"), "up to date: up to date");
}

TEST_F(FileFreshness, TruncatedFileIsBakedAgain) {
  const fs::path exr = scene_dir() / "transmittance.exr";
  const auto size = fs::file_size(exr);
  fs::resize_file(exr, size / 2);
  const auto s = statuses(bake_scene(scene_, options_));
  EXPECT_EQ(s.at("transmittance"),
            fmt::format("baked: file transmittance.exr changed size ({} -> {} bytes)", size,
                        size / 2));
  EXPECT_EQ(fs::file_size(exr), size);
  EXPECT_EQ(s.at("multiscattering"), "up to date: up to date") << "its values did not change";
}

TEST_F(FileFreshness, FileEditedInPlaceIsBakedAgain) {
  overwrite_byte(scene_dir() / "transmittance.dds", 200);  // its time changes with the write
  const auto s = statuses(bake_scene(scene_, options_));
  EXPECT_EQ(s.at("transmittance"), "baked: file transmittance.dds changed content");
}

TEST_F(FileFreshness, EditWithTheTimePutBackIsCaughtByVerify) {
  const fs::path dds = scene_dir() / "transmittance.dds";
  const int64_t t = stat_file(dds).mtime_ns;
  overwrite_byte(dds, 200);
  set_mtime_ns(dds, t);
  // Size and time match the record: the cheap check trusts the file...
  EXPECT_EQ(statuses(bake_scene(scene_, options_)).at("transmittance"), "up to date: up to date");
  // ...verify hashes it.
  BakeOptions verify = options_;
  verify.verify = true;
  EXPECT_EQ(statuses(bake_scene(scene_, verify)).at("transmittance"),
            "baked: file transmittance.dds changed content");
}

TEST_F(FileFreshness, MissingLogCostsAHashNotARebake) {
  fs::remove(scene_dir() / "bake_log.json");
  const auto s = statuses(bake_scene(scene_, options_));
  EXPECT_EQ(s.at("transmittance"), "up to date: up to date");
  EXPECT_TRUE(fs::exists(scene_dir() / "bake_log.json")) << "the verified times are logged again";
}

}  // namespace

namespace {

// The same through the command line: plan names the reason, `bake --verify`
// catches the edit whose time was put back.
TEST_F(FileFreshness, PlanNamesTheReasonAndBakeVerifyRepairs) {
  const fs::path dds = scene_dir() / "transmittance.dds";
  const int64_t t = stat_file(dds).mtime_ns;
  overwrite_byte(dds, 200);
  set_mtime_ns(dds, t);
  const std::string preset = scene_.file.string(), out = (dir_ / "out").string();
  auto plan = test::run_skybake({"plan", preset, "-o", out, "--json"});
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_EQ(plan.out.find("changed content"), std::string::npos) << "size and time match";
  auto bake = test::run_skybake({"bake", preset, "-o", out, "--verify", "--json"});
  ASSERT_EQ(bake.exit_code, 0) << bake.err;
  const auto j = nlohmann::json::parse(bake.out);
  std::string reason;
  for (const auto& o : j["scenes"][0]["outputs"])
    if (o["product"] == "transmittance") reason = o["status"].get<std::string>() + ": " + o["reason"].get<std::string>();
  EXPECT_EQ(reason, "baked: file transmittance.dds changed content");
  overwrite_byte(dds, 300);  // a plain edit changes the time: plan sees it without --verify
  plan = test::run_skybake({"plan", preset, "-o", out, "--json"});
  EXPECT_NE(plan.out.find("file transmittance.dds changed content"), std::string::npos) << plan.out;
}

}  // namespace

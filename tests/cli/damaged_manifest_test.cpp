// manifest.json edited after the bake that wrote it, through the real
// executable: a record of the wrong type, a record whose content no longer
// matches what the bake wrote, junk records. Each is a damaged record: set
// aside with one note naming the file, its output baked again, and the
// manifest left equal, byte for byte, to the one a clean bake writes.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using nlohmann::json;
using skybake::test::read_file;
using skybake::test::run_skybake;

namespace {

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// One scene with a transmittance table and a weather map, baked into `out`
// next to the scene file; `scene` is the same path for every bake, so that
// the manifests' "preset" fields agree.
struct Folder {
  fs::path dir, scene, out, manifest;
};

Folder scene_folder(const fs::path& dir) {
  Folder f{dir, dir / "scene.json", dir / "out", dir / "out" / "damaged" / "manifest.json"};
  const json scene = {
      {"name", "damaged"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", skybake::test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs",
       {{{"product", "transmittance"}, {"size", {32, 16}}, {"formats", {"exr"}}},
        {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}}}}}};
  write(f.scene, scene.dump(2));
  return f;
}

skybake::test::RunResult bake(const Folder& f, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"bake", f.scene.string(), "-o", f.out.string(), "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_skybake(args);
}

// The manifest a bake of the same scene file into an empty folder writes.
std::string clean_manifest(Folder f) {
  f.out = f.dir / "clean_out";
  const auto r = bake(f);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_file(f.out / "damaged" / "manifest.json");
}

// How the bake reported each output: "baked" or "up to date", by name.
std::map<std::string, std::string> statuses(const std::string& bake_json) {
  std::map<std::string, std::string> s;
  const json report = json::parse(bake_json);
  for (const json& o : report["scenes"][0]["outputs"])
    s[o["name"].get<std::string>()] = o["status"].get<std::string>();
  return s;
}

class DamagedManifest : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = scene_folder(skybake::test::test_dir("cli_damaged_manifest"));
    clean_ = clean_manifest(folder_);
    const auto r = bake(folder_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(read_file(folder_.manifest), clean_);
  }

  // Writes the manifest with `value` at `pointer`, then checks that plan and
  // info read it without an internal error, and that a bake notes the
  // damaged record, bakes `rebaked` again and leaves the clean manifest.
  void expect_repaired(const std::string& pointer, const json& value,
                       const std::string& rebaked, const std::string& note,
                       const std::vector<std::string>& flags = {}) {
    json m = json::parse(clean_);
    m[json::json_pointer(pointer)] = value;
    expect_repaired(m, rebaked, note, flags);
  }

  // As above for a whole edited manifest `m`; `rebaked` empty: nothing is.
  void expect_repaired(const json& m, const std::string& rebaked, const std::string& note,
                       const std::vector<std::string>& flags = {}) {
    SCOPED_TRACE(m.dump().substr(0, 200));
    write(folder_.manifest, m.dump(2));
    const auto plan = run_skybake({"plan", folder_.scene.string(), "-o", folder_.out.string()});
    EXPECT_EQ(plan.exit_code, 0) << plan.err;
    const fs::path table = folder_.manifest.parent_path() / "transmittance.exr";
    const auto info = run_skybake({"info", table.string()});
    EXPECT_EQ(info.exit_code, 0) << info.err;
    const auto r = bake(folder_, flags);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr(folder_.manifest.string() + ": 1 damaged record set aside (" +
                                 note));
    EXPECT_EQ(r.err.find("damaged record", r.err.find("damaged record") + 1), std::string::npos)
        << "one note: " << r.err;
    if (!rebaked.empty()) EXPECT_EQ(statuses(r.out)[rebaked], "baked") << r.out;
    for (const auto& [name, status] : statuses(r.out))
      if (name != rebaked && flags.empty()) EXPECT_EQ(status, "up to date") << name;
    EXPECT_EQ(read_file(folder_.manifest), clean_);
    const auto again = bake(folder_);
    EXPECT_EQ(again.err.find("damaged record"), std::string::npos) << again.err;
  }

  std::string clean_;
  Folder folder_;
};

TEST_F(DamagedManifest, WronglyTypedWarningsAreRebuilt) {
  expect_repaired("/outputs/1/warnings", json::array({5}), "transmittance",
                  "/outputs/1/warnings/0: expected an object");
  expect_repaired("/outputs/1/warnings", json::array({{{"code", 5}, {"message", "m"}}}),
                  "transmittance", "/outputs/1/warnings/0/code: expected a non-empty string");
  expect_repaired("/outputs/1/warnings", json::array({{{"code", "c"}, {"message", {1, 2}}}}),
                  "transmittance", "/outputs/1/warnings/0/message: expected a string");
  expect_repaired("/outputs/0/warnings", json::array({{{"code", "c"}}}), "multiscattering",
                  "/outputs/0/warnings/0/message: expected a string");
}

TEST_F(DamagedManifest, AnEditedValueIsCaughtByTheEntryHashAndRebaked) {
  const json clean = json::parse(clean_);
  ASSERT_EQ(clean["outputs"][1]["metadata"]["top_radius_m"], 6460000.0);
  expect_repaired("/outputs/1/metadata/top_radius_m", 6460001.0, "transmittance",
                  "/outputs/1: the entry does not match its entry_hash");
  expect_repaired("/outputs/0/warnings", json::array({{{"code", "c"}, {"message", "m"}}}),
                  "multiscattering", "/outputs/0: the entry does not match its entry_hash");
  expect_repaired("/outputs/0/extra", 1, "multiscattering",
                  "/outputs/0: the entry does not match its entry_hash");
  expect_repaired("/outputs/1/entry_hash", "0000000000000000", "transmittance",
                  "/outputs/1: the entry does not match its entry_hash");
}

TEST_F(DamagedManifest, JunkAndRepeatedEntriesAreDroppedEvenUnderForce) {
  json junk = json::parse(clean_);
  junk["outputs"].push_back(json::object());
  expect_repaired(junk, "", "/outputs/2: missing required key 'product'");
  expect_repaired(junk, "", "/outputs/2: missing required key 'product'", {"--force"});
  json twice = json::parse(clean_);
  twice["outputs"].push_back(twice["outputs"][0]);
  expect_repaired(twice, "", "/outputs/2: a second entry named 'multiscattering'");
  json nameless = json::parse(clean_);
  nameless["outputs"][0]["name"] = "";
  expect_repaired(nameless, "multiscattering",
                  "/outputs/0/name: expected a non-empty string");
}

}  // namespace

// bake_scene (pipeline/bake.hpp) on a small scene: which outputs a bake
// finds current and why, what it computes or reads back, what a failure
// leaves on disk, and that on_recorded names exactly what the manifest lists.
#include "pipeline/bake.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/file_record.hpp"
#include "io/manifest.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

// Transmittance in two formats and the multiple-scattering table that reads
// it, small enough to bake in a fraction of a second; the atmosphere inline
// so a test can edit it.
json small_preset() {
  json atmosphere =
      json::parse(test::read_file(test::source_path("presets/atmospheres/earth.json")));
  atmosphere.erase("$schema");
  return {{"name", "small"},
          {"description", "two small tables"},
          {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
          {"atmosphere", atmosphere},
          {"outputs", json::array({json::object({{"product", "transmittance"},
                                                 {"size", {32, 16}},
                                                 {"formats", {"exr", "dds"}}}),
                                   json::object({{"product", "multiscattering"},
                                                 {"size", {8, 8}},
                                                 {"formats", {"exr"}},
                                                 {"directions", 16}})})}};
}

// (name, input hash) of each on_recorded call.
using Recorded = std::set<std::pair<std::string, std::string>>;

class Bake : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::test_dir("bake");
    options_.out_dir = dir_ / "out";
    options_.on_recorded = [this](const fs::path& scene_dir, const std::string& name,
                                  const std::string& hash) {
      EXPECT_EQ(scene_dir, this->scene_dir());
      recorded_.insert({name, hash});
    };
  }

  Scene load(const json& preset) {
    const fs::path file = dir_ / "small.json";
    std::ofstream(file) << preset.dump(2);
    return load_scene(file);
  }

  BakeSummary bake(const json& preset) {
    recorded_.clear();
    return bake_scene(load(preset), options_);
  }

  fs::path scene_dir() const { return dir_ / "out" / "small"; }
  Manifest manifest() const { return read_manifest(scene_dir() / "manifest.json"); }

  // What the manifest lists, as on_recorded reports it.
  Recorded listed() const {
    Recorded out;
    const Manifest m = manifest();
    for (const auto& [name, entry] : m.entries) out.insert({name, entry.input_hash});
    return out;
  }

  // Modification time of every file in the scene folder.
  std::map<std::string, int64_t> mtimes() const {
    std::map<std::string, int64_t> out;
    for (const std::string& f : test::list_files(scene_dir()))
      out[f] = stat_file(scene_dir() / f).mtime_ns;
    return out;
  }

  fs::path dir_;
  BakeOptions options_;
  Recorded recorded_;
};

// product -> "status: reason"
std::map<std::string, std::string> statuses(const BakeSummary& s) {
  std::map<std::string, std::string> out;
  for (const OutputRecord& r : s.outputs) out[r.product] = r.status + ": " + r.reason;
  return out;
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const std::string& f : test::list_files(dir))
    if (is_temporary_name(fs::path(f).filename().string())) found.push_back(f);
  return found;
}

TEST_F(Bake, FirstBakeBakesEverythingNotBakedYet) {
  const BakeSummary s = bake(small_preset());
  EXPECT_EQ(statuses(s),
            (std::map<std::string, std::string>{{"transmittance", "baked: not baked yet"},
                                                {"multiscattering", "baked: not baked yet"}}));
  EXPECT_EQ(s.computed, (std::vector<std::string>{"transmittance", "multiscattering"}));
  EXPECT_TRUE(s.loaded.empty());
  for (const char* f : {"transmittance.exr", "transmittance.dds", "multiscattering.exr"})
    EXPECT_TRUE(fs::exists(scene_dir() / f)) << f;
  EXPECT_EQ(recorded_, listed());
  EXPECT_EQ(recorded_.size(), 2u);
  EXPECT_TRUE(temporaries(scene_dir()).empty());
}

// Writing an output's files (block compression can take longer than the
// bake) shows on the progress line: each file is named as it is written,
// with the share of the output's files done, after the bake's own reports.
TEST_F(Bake, ProgressNamesEachFileWhileItIsWritten) {
  std::vector<std::pair<std::string, double>> reports;
  options_.on_progress = [&reports](const std::string& label, double f) {
    reports.push_back({label, f});
  };
  bake(small_preset());
  auto at = [&](const std::string& label) {
    for (size_t i = 0; i < reports.size(); ++i)
      if (reports[i].first == label) return i;
    ADD_FAILURE() << "no report '" << label << "'";
    return reports.size();
  };
  const size_t exr = at("transmittance writing transmittance.exr");
  const size_t dds = at("transmittance writing transmittance.dds");
  ASSERT_LT(exr, dds);
  ASSERT_LT(dds, reports.size());
  EXPECT_EQ(reports[exr].second, 0.0);
  EXPECT_EQ(reports[dds].second, 0.5);
  for (size_t i = 0; i < exr; ++i)
    EXPECT_EQ(reports[i].first.find("multiscattering"), std::string::npos)
        << "transmittance is written before multiscattering is baked";
  const size_t ms = at("multiscattering writing multiscattering.exr");
  EXPECT_GT(ms, dds);
  EXPECT_EQ(reports.back().first, "multiscattering writing multiscattering.exr");
}

TEST_F(Bake, SecondBakeIsUpToDateAndDoesNoWork) {
  bake(small_preset());
  const std::string manifest_before = test::read_file(scene_dir() / "manifest.json");
  const auto times_before = mtimes();
  const BakeSummary s = bake(small_preset());
  EXPECT_EQ(statuses(s),
            (std::map<std::string, std::string>{{"transmittance", "up to date: up to date"},
                                                {"multiscattering", "up to date: up to date"}}));
  EXPECT_TRUE(s.computed.empty());
  EXPECT_TRUE(s.loaded.empty());
  EXPECT_EQ(test::read_file(scene_dir() / "manifest.json"), manifest_before);
  for (const char* f : {"transmittance.exr", "transmittance.dds", "multiscattering.exr"})
    EXPECT_EQ(mtimes().at(f), times_before.at(f)) << f << " was rewritten";
  // Current outputs are reported recorded too (the farm's stamps follow them).
  EXPECT_EQ(recorded_, listed());
}

TEST_F(Bake, EditedSectionChangesTheInputsOfWhatReadsIt) {
  bake(small_preset());
  const Recorded before = listed();
  json edited = small_preset();
  edited["atmosphere"]["rayleigh"]["scattering_per_m"][0] = 6.0e-6;
  const BakeSummary s = bake(edited);
  for (const OutputRecord& r : s.outputs) {
    EXPECT_EQ(r.status, "baked") << r.product;
    EXPECT_EQ(r.reason.rfind("inputs changed", 0), 0u) << r.product << ": " << r.reason;
  }
  EXPECT_EQ(s.outputs.size(), 2u);
  EXPECT_EQ(s.computed, (std::vector<std::string>{"transmittance", "multiscattering"}));
  // New hashes in the manifest, and on_recorded named them.
  for (const auto& entry : listed()) EXPECT_EQ(before.count(entry), 0u) << entry.first;
  EXPECT_EQ(recorded_, listed());
}

TEST_F(Bake, AKeyNoProductReadsInvalidatesNothing) {
  bake(small_preset());
  json edited = small_preset();
  edited["description"] = "the same two tables, described differently";
  const BakeSummary s = bake(edited);
  for (const OutputRecord& r : s.outputs) EXPECT_EQ(r.status, "up to date") << r.product;
  EXPECT_EQ(s.outputs.size(), 2u);
  EXPECT_TRUE(s.computed.empty());
}

TEST_F(Bake, DeletedFileIsMissingAndOnlyItsOutputIsBaked) {
  bake(small_preset());
  const auto times_before = mtimes();
  fs::remove(scene_dir() / "transmittance.dds");
  const BakeSummary s = bake(small_preset());
  EXPECT_EQ(statuses(s), (std::map<std::string, std::string>{
                             {"transmittance", "baked: missing file transmittance.dds"},
                             {"multiscattering", "up to date: up to date"}}));
  EXPECT_EQ(s.computed, std::vector<std::string>{"transmittance"});
  EXPECT_TRUE(fs::exists(scene_dir() / "transmittance.dds"));
  EXPECT_EQ(mtimes().at("multiscattering.exr"), times_before.at("multiscattering.exr"));
}

TEST_F(Bake, ForceBakesWhatIsCurrent) {
  bake(small_preset());
  options_.force = true;
  const BakeSummary s = bake(small_preset());
  EXPECT_EQ(statuses(s),
            (std::map<std::string, std::string>{{"transmittance", "baked: forced"},
                                                {"multiscattering", "baked: forced"}}));
  EXPECT_EQ(s.computed, (std::vector<std::string>{"transmittance", "multiscattering"}));
  EXPECT_EQ(recorded_, listed());
}

TEST_F(Bake, ChangedFormatRewritesThatOutputButNotItsDependents) {
  // Formats shape files, not values: the transmittance's files are written
  // again, the table that reads its values stays current.
  bake(small_preset());
  const auto times_before = mtimes();
  json edited = small_preset();
  edited["outputs"][0]["formats"] = {"exr"};
  const BakeSummary s = bake(edited);
  const auto st = statuses(s);
  EXPECT_EQ(st.at("transmittance").rfind("baked: inputs changed", 0), 0u) << st.at("transmittance");
  EXPECT_EQ(st.at("multiscattering"), "up to date: up to date");
  EXPECT_EQ(s.computed, std::vector<std::string>{"transmittance"});
  EXPECT_EQ(mtimes().at("multiscattering.exr"), times_before.at("multiscattering.exr"));
  const Manifest m = manifest();
  const ManifestEntry& t = m.entries.at("transmittance");
  ASSERT_EQ(t.files.size(), 1u);
  EXPECT_EQ(t.files[0].path, "transmittance.exr");
}

TEST_F(Bake, FailureAfterAWrittenOutputKeepsItRecordedAndLeavesNoPartialFiles) {
  // The multiple-scattering table's DDS cannot hold RGB in R8_UNORM (load_scene
  // refuses that, so the spec changes after loading): it fails after its EXR
  // went to a temporary, and after the transmittance was written.
  json broken = small_preset();
  broken["outputs"][1]["formats"] = {"exr", "dds"};
  Scene scene = load(broken);
  scene.outputs[1].options["dds_format"] = "R8_UNORM";
  recorded_.clear();
  EXPECT_THROW(bake_scene(scene, options_), IoError);

  const Manifest m = manifest();
  EXPECT_EQ(m.entries.count("transmittance"), 1u);
  EXPECT_EQ(m.entries.count("multiscattering"), 0u);
  EXPECT_TRUE(fs::exists(scene_dir() / "transmittance.exr"));
  EXPECT_FALSE(fs::exists(scene_dir() / "multiscattering.exr"));
  EXPECT_FALSE(fs::exists(scene_dir() / "multiscattering.dds"));
  EXPECT_TRUE(temporaries(scene_dir()).empty()) << temporaries(scene_dir()).front();
  // on_recorded named the written output only: a stamp never claims more
  // than the manifest lists.
  EXPECT_EQ(recorded_, listed());
  EXPECT_EQ(recorded_.size(), 1u);

  // The next bake finds the written one current and reads it back.
  const BakeSummary s = bake(small_preset());
  EXPECT_EQ(statuses(s).at("transmittance"), "up to date: up to date");
  EXPECT_EQ(s.loaded, std::vector<std::string>{"transmittance"});
  EXPECT_EQ(s.computed, std::vector<std::string>{"multiscattering"});
}

TEST_F(Bake, OnlyComputesWhatItNeedsAndReadsCurrentDependenciesBack) {
  // Nothing on disk: the dependency is computed in memory, not written.
  options_.only = {"multiscattering"};
  BakeSummary s = bake(small_preset());
  EXPECT_EQ(s.computed, (std::vector<std::string>{"transmittance", "multiscattering"}));
  EXPECT_TRUE(s.loaded.empty());
  EXPECT_EQ(statuses(s),
            (std::map<std::string, std::string>{{"multiscattering", "baked: not baked yet"}}));
  EXPECT_FALSE(fs::exists(scene_dir() / "transmittance.exr"));
  EXPECT_EQ(recorded_, listed());
  EXPECT_EQ(recorded_.size(), 1u);

  // The dependency alone: its dependent is not touched.
  options_.only = {"transmittance"};
  s = bake(small_preset());
  EXPECT_EQ(s.computed, std::vector<std::string>{"transmittance"});
  EXPECT_EQ(statuses(s),
            (std::map<std::string, std::string>{{"transmittance", "baked: not baked yet"}}));

  // Both current on disk: a forced dependent reads its dependency back.
  options_.only = {"multiscattering"};
  options_.force = true;
  s = bake(small_preset());
  EXPECT_EQ(s.loaded, std::vector<std::string>{"transmittance"});
  EXPECT_EQ(s.computed, std::vector<std::string>{"multiscattering"});
  ASSERT_EQ(recorded_.size(), 1u);
  EXPECT_EQ(recorded_.begin()->first, "multiscattering");
}

}  // namespace
}  // namespace skybake

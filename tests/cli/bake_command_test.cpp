// End-to-end tests of `skybake bake` on the shipped Earth preset: files,
// manifest, incremental re-runs, --force, --only, determinism across thread
// counts and the --json summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "io/texture_file.hpp"
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

TEST(BakeCommand, ManifestRecordsMeasuredErrorAndTimeOfEveryLut) {
  const fs::path out = fresh_dir("bake_error_measures");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q"}).exit_code, 0);
  const auto manifest = nlohmann::json::parse(read_file(out / "earth/manifest.json"));
  const auto log = nlohmann::json::parse(read_file(out / "earth/bake_log.json"));
  // Earth's tables read as an engine reads them (docs/report.md gives the
  // report's figures; tests/report/bake_error_test.cpp holds the two within 2x).
  const std::map<std::string, double> bound = {{"transmittance", 0.05},
                                               {"multiscattering", 2.0},
                                               {"skyview", 0.02},
                                               {"aerial_perspective", 0.5}};
  size_t checked = 0;
  for (const auto& o : manifest["outputs"]) {
    const std::string product = o["product"];
    const auto& logged = log["outputs"][o["name"].get<std::string>()];
    EXPECT_GT(logged["bake_seconds"].get<double>(), 0.0) << product;
    EXPECT_FALSE(o.contains("estimated_error")) << product;
    if (!bound.count(product)) {
      EXPECT_TRUE(o["error"].is_null()) << product;
      continue;
    }
    EXPECT_GT(logged["error_seconds"].get<double>(), 0.0) << product;
    const auto& e = o["error"];
    ASSERT_TRUE(e.is_object()) << product;
    EXPECT_GT(e["queries"].get<int>(), 0) << product;
    EXPECT_FALSE(e["reference"].get<std::string>().empty()) << product;
    EXPECT_GT(e["max_rel"].get<double>(), 0.0) << product;
    EXPECT_LT(e["max_rel"].get<double>(), bound.at(product)) << product;
    EXPECT_LE(e["rms_rel"].get<double>(), e["max_rel"].get<double>()) << product;
    EXPECT_TRUE(o["warnings"].empty()) << product;
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
  // The manifest too: the measured errors do not depend on the thread count.
  for (const std::string f :
       {"earth/transmittance.exr", "earth/transmittance.dds", "earth/manifest.json"}) {
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
    // Held in a variable: a loop over a member of parse()'s temporary would
    // read a destroyed object.
    const nlohmann::json summary = nlohmann::json::parse(r.out);
    int checked = 0;
    for (const auto& o : summary["scenes"][0]["outputs"])
      for (const auto& f : o["files"]) {
        const std::string path = f["path"].get<std::string>();
        ASSERT_TRUE(fs::exists(path)) << path;
        if (f["format"] == "png") continue;  // a picture, not data
        const skybake::Texture tex = skybake::read_texture_file(path).texture;
        EXPECT_GT(tex.data.size(), 0u) << path;
        EXPECT_TRUE(std::all_of(tex.data.begin(), tex.data.end(),
                                [](float v) { return std::isfinite(v); }))
            << path;
        ++checked;
      }
    EXPECT_GE(checked, 4) << p << ": the summary lists too few files";
  }
}

}  // namespace

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  return lines;
}

TEST(BakeCommand, EndsWithOneSummaryLine) {
  const fs::path out = fresh_dir("bake_summary");
  const std::string only = "transmittance,multiscattering";
  auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", only});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(lines[0].substr(0, 24), "baked      transmittance");
  EXPECT_TRUE(std::regex_match(lines[2],
                               std::regex(R"(skybake: 2 baked, 0 up to date, 0 warnings, \d+\.\d\d s)")))
      << lines[2];

  r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", only});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_TRUE(std::regex_match(lines[2],
                               std::regex(R"(skybake: 0 baked, 2 up to date, 0 warnings, \d+\.\d\d s)")))
      << lines[2];

  r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", only, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
}

TEST(BakeCommand, JsonCarriesTheSummaryNumbers) {
  const fs::path out = fresh_dir("bake_summary_json");
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q", "--only", "transmittance"})
                .exit_code,
            0);
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--json", "--only",
                              "transmittance,multiscattering"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // nothing but the document on stdout
  const auto& summary = j["summary"];
  EXPECT_EQ(summary["baked"], 1);
  EXPECT_EQ(summary["up_to_date"], 1);
  EXPECT_EQ(summary["warnings"], 0);
  EXPECT_EQ(j["scenes"][0]["warnings"], nlohmann::json::array());
  EXPECT_GE(summary["seconds"].get<double>(), j["scenes"][0]["seconds"].get<double>());
  EXPECT_EQ(r.err, "");
}

// -v is the farm log: timestamped lines on stderr saying why each output was
// (not) baked, what was read back or computed in memory, threads and times.
TEST(BakeCommand, VerboseLogsWhyAndHow) {
  const fs::path dir = fresh_dir("bake_verbose");
  fs::copy(source_path("presets/atmospheres"), dir / "atmospheres");
  fs::copy_file(kEarth, dir / "earth.json");
  const std::string preset = (dir / "earth.json").string(), out = (dir / "out").string();
  const std::regex line(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3} skybake\[\d+\] (.*))");
  const auto log = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"bake", preset, "-o", out, "-v", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_skybake(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "") << "-q: nothing on stdout";
    std::string messages;
    for (const std::string& l : lines_of(r.err)) {
      std::smatch m;
      EXPECT_TRUE(std::regex_match(l, m, line)) << l;
      messages += m[1].str() + "\n";
    }
    return messages;
  };
  auto has = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };

  std::string m = log({"--only", "transmittance,multiscattering", "--threads", "1"});
  EXPECT_TRUE(has(m, "bake 1 scene into " + out + " with 1 thread\n")) << m;
  EXPECT_TRUE(has(m, "earth: " + preset + " -> " + out + "/earth\n")) << m;
  EXPECT_TRUE(std::regex_search(m, std::regex(R"(earth/transmittance: baked in \d+\.\d{3} s \(not baked yet\)\n)")))
      << m;
  EXPECT_TRUE(has(m, "dependencies read back from disk: none; computed in memory only: none\n"))
      << m;

  m = log({"--only", "skyview", "--threads", "2"});
  EXPECT_TRUE(has(m, "with 2 threads\n")) << m;
  EXPECT_TRUE(has(m, "earth/skyview: baked in ")) << m;
  EXPECT_TRUE(has(m, "dependencies read back from disk: transmittance, multiscattering; "
                     "computed in memory only: none\n"))
      << m;

  fs::remove(dir / "out/earth/transmittance.dds");
  m = log({"--only", "transmittance,multiscattering,skyview"});
  EXPECT_TRUE(has(m, "(missing file transmittance.dds)\n")) << m;
  EXPECT_TRUE(has(m, "earth/multiscattering: up to date\n")) << m;

  std::string text = read_file(dir / "earth.json");
  text.replace(text.find("[256, 64]"), 9, "[128, 32]");
  std::ofstream(dir / "earth.json", std::ios::binary) << text;
  m = log({"--only", "transmittance", "--force"});
  EXPECT_TRUE(has(m, "with 1 thread, --force\n") || has(m, "threads, --force\n")) << m;
  EXPECT_TRUE(std::regex_search(
      m, std::regex(R"(earth/transmittance: baked in \S+ s \(inputs changed \(hash [0-9a-f]{16} -> [0-9a-f]{16}\)\)\n)")))
      << m;
  // The new transmittance is current on disk; multiscattering, which reads
  // it, is stale and only computed in memory for skyview.
  m = log({"--only", "skyview"});
  EXPECT_TRUE(has(m, "dependencies read back from disk: transmittance; computed in memory only: "
                     "multiscattering\n"))
      << m;
}

TEST(BakeCommand, WithoutVerboseStderrStaysEmpty) {
  const fs::path out = fresh_dir("bake_not_verbose");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", "transmittance"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// On a terminal the progress line shows the elapsed time and an ETA.
TEST(BakeCommand, ProgressLineOnATerminalShowsElapsedAndEta) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  // A sky-view table 25 times the preset's, so the bake lasts long enough
  // (a few seconds on one thread) for an ETA.
  const fs::path dir = fresh_dir("bake_progress");
  fs::copy(source_path("presets/atmospheres"), dir / "atmospheres");
  std::string text = read_file(kEarth);
  text.replace(text.find("[192, 108]"), 10, "[960, 540]");
  std::ofstream(dir / "earth.json", std::ios::binary) << text;
  const fs::path typescript = dir / "typescript";
  const std::string cmd = skybake::test::skybake_exe() + " bake " + (dir / "earth.json").string() +
                          " -o " + (dir / "out").string() + " --only skyview --threads 1";
  const std::string shell = "script -qec '" + cmd + "' /dev/null >" + typescript.string() + " 2>&1";
  ASSERT_EQ(std::system(shell.c_str()), 0) << read_file(typescript);
  const std::string tty = read_file(typescript);
  EXPECT_TRUE(std::regex_search(tty, std::regex(R"(earth/skyview \[[#.]{24}\] +\d+%  \S+ s, ETA \d)")))
      << tty;
  EXPECT_TRUE(std::regex_search(tty, std::regex(R"(skybake: 1 baked, 0 up to date, 0 warnings)"))) << tty;
}

}  // namespace

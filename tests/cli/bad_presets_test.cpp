// Every malformed preset of tests/bad_presets/ (index: EXPECTED.json) gives a
// non-zero exit from `validate` and `bake`, one error naming the file, the
// JSON pointer and the rule of its first problem, then one line per further
// problem ("more" in EXPECTED.json, in that order), and writes nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using skybake::test::fresh_dir;
using skybake::test::list_files;
using skybake::test::read_file;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

nlohmann::json expected_index() {
  return nlohmann::json::parse(read_file(source_path("tests/bad_presets/EXPECTED.json")));
}

size_t count_lines(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// Lines of the error: the first problem's, then one per further problem.
size_t expected_lines(const nlohmann::json& want) {
  return 1 + want.value("more", nlohmann::json::array()).size();
}

TEST(BadPresets, CorpusIsLargeEnough) { EXPECT_GE(expected_index().size(), 25u); }

TEST(BadPresets, ValidateRejectsEachWithFilePointerAndRule) {
  const nlohmann::json index = expected_index();
  for (const auto& [file, want] : index.items()) {
    const std::string path = source_path("tests/bad_presets/" + file).string();
    const auto r = run_skybake({"validate", path});
    if (want.contains("validate")) {  // a valid preset of another kind than a scene
      EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
      continue;
    }
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_EQ(count_lines(r.err), expected_lines(want)) << file << ": " << r.err;
    EXPECT_NE(r.err.find("skybake: error: "), std::string::npos) << file << ": " << r.err;
    const std::string pointer = want["pointer"];
    const std::string rule = want["rule"];
    const std::string named_file = want.value("file", file);
    EXPECT_NE(r.err.find(named_file), std::string::npos) << file << ": " << r.err;
    EXPECT_NE(r.err.find(pointer + ":"), std::string::npos)
        << file << ": expected pointer " << pointer << " in: " << r.err;
    EXPECT_NE(r.err.find(rule), std::string::npos)
        << file << ": expected rule '" << rule << "' in: " << r.err;
    // Each further problem on its own line, in order: "  <file>: <pointer>: <rule>".
    std::vector<std::string> lines;
    for (size_t start = 0, end; (end = r.err.find('\n', start)) != std::string::npos;
         start = end + 1)
      lines.push_back(r.err.substr(start, end - start));
    const nlohmann::json more = want.value("more", nlohmann::json::array());
    for (size_t k = 0; k < more.size() && k + 1 < lines.size(); ++k) {
      const std::string& line = lines[k + 1];
      EXPECT_EQ(line.rfind("  ", 0), 0u) << file << ": " << line;
      EXPECT_NE(line.find(more[k].value("file", named_file)), std::string::npos) << line;
      EXPECT_NE(line.find(": " + more[k]["pointer"].get<std::string>() + ": "), std::string::npos)
          << file << ": expected " << more[k] << " in: " << line;
      EXPECT_NE(line.find(more[k]["rule"].get<std::string>()), std::string::npos)
          << file << ": expected " << more[k] << " in: " << line;
    }
  }
}

TEST(BadPresets, BakeRejectsEachAndWritesNothing) {
  const nlohmann::json index = expected_index();
  for (const auto& [file, want] : index.items()) {
    const fs::path out = fresh_dir("bad_preset_out");
    const std::string path = source_path("tests/bad_presets/" + file).string();
    const auto r = run_skybake({"bake", path, "-o", out.string()});
    EXPECT_EQ(r.exit_code, 3) << file << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), expected_lines(want)) << file << ": " << r.err;
    EXPECT_TRUE(list_files(out).empty()) << file << " wrote files";
  }
}

TEST(BadPresets, OneBadPresetStopsTheRunBeforeAnyWrite) {
  const fs::path out = fresh_dir("bad_preset_mixed");
  const std::string good = source_path("presets/earth.json").string();
  const std::string bad =
      source_path("tests/bad_presets/" + expected_index().begin().key()).string();
  const auto r = run_skybake({"bake", good, bad, "-o", out.string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(list_files(out).empty());
}

TEST(BadPresets, ValidateAcceptsShippedPresets) {
  for (const std::string p : {"presets/earth.json", "presets/mars.json", "presets/tiny_planet.json"}) {
    const auto r = run_skybake({"validate", source_path(p).string()});
    EXPECT_EQ(r.exit_code, 0) << p << ": " << r.err;
  }
}

}  // namespace

// Every malformed preset of tests/bad_presets/ (index: EXPECTED.json) gives a
// non-zero exit from `validate` and `bake`, ONE error message naming the file,
// the JSON pointer and the rule, and writes nothing.
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

TEST(BadPresets, CorpusIsLargeEnough) { EXPECT_GE(expected_index().size(), 25u); }

TEST(BadPresets, ValidateRejectsEachWithFilePointerAndRule) {
  const nlohmann::json index = expected_index();
  for (const auto& [file, want] : index.items()) {
    const std::string path = source_path("tests/bad_presets/" + file).string();
    const auto r = run_skybake({"validate", path});
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_EQ(count_lines(r.err), 1u) << file << ": " << r.err;
    EXPECT_NE(r.err.find("skybake: error: "), std::string::npos) << file << ": " << r.err;
    const std::string pointer = want["pointer"];
    const std::string rule = want["rule"];
    const std::string named_file = want.value("file", file);
    EXPECT_NE(r.err.find(named_file), std::string::npos) << file << ": " << r.err;
    EXPECT_NE(r.err.find(pointer + ":"), std::string::npos)
        << file << ": expected pointer " << pointer << " in: " << r.err;
    EXPECT_NE(r.err.find(rule), std::string::npos)
        << file << ": expected rule '" << rule << "' in: " << r.err;
  }
}

TEST(BadPresets, BakeRejectsEachAndWritesNothing) {
  const nlohmann::json index = expected_index();
  for (const auto& [file, want] : index.items()) {
    const fs::path out = fresh_dir("bad_preset_out");
    const std::string path = source_path("tests/bad_presets/" + file).string();
    const auto r = run_skybake({"bake", path, "-o", out.string()});
    EXPECT_EQ(r.exit_code, 3) << file << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << file << ": " << r.err;
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

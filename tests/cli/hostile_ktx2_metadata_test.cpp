// A KTX2 file skybake wrote, with one key/value entry forged to hold JSON
// nested far deeper than any file skybake writes: `info` and `check-tiling`
// must refuse it as a file error (exit 4) naming the limit, never recurse
// into it (a crash is exit code -1 here) or quote it back in full.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/file_bytes.hpp"
#include "support/ktx2_edit.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using skybake::test::run_skybake;

namespace {

// A transmittance table baked as KTX2 by the real executable.
fs::path baked_ktx2(const fs::path& dir) {
  const nlohmann::json scene = {
      {"name", "deepkv"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", skybake::test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs",
       {{{"product", "transmittance"}, {"size", {32, 16}}, {"formats", {"ktx2"}}}}}};
  std::ofstream(dir / "scene.json") << scene.dump();
  const auto r = run_skybake(
      {"bake", (dir / "scene.json").string(), "-o", (dir / "out").string(), "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir / "out" / "deepkv" / "transmittance.ktx2";
}

std::string nested_arrays(size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

class DeepKeyValue : public testing::TestWithParam<std::string> {};

TEST_P(DeepKeyValue, InfoAndCheckTilingRefuseItAsAFileError) {
  const fs::path dir = skybake::test::test_dir("cli_deep_kv");
  const fs::path file = baked_ktx2(dir);
  ASSERT_TRUE(fs::exists(file));
  const std::string key = GetParam();
  const fs::path forged = dir / "forged.ktx2";
  skybake::test::write_bytes(
      forged, skybake::test::with_ktx2_key_value(skybake::test::read_bytes(file), key,
                                                 nested_arrays(100000) + '\0'));
  // The untouched key/value entries still read: the edit itself is sound.
  const fs::path shallow = dir / "shallow.ktx2";
  skybake::test::write_bytes(
      shallow, skybake::test::with_ktx2_key_value(skybake::test::read_bytes(file),
                                                  "skybake.note", std::string("\"x\"") + '\0'));
  const auto ok = run_skybake({"info", shallow.string()});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;

  for (const char* command : {"info", "check-tiling"}) {
    SCOPED_TRACE(command);
    const auto r = run_skybake({command, forged.string()});
    EXPECT_EQ(r.exit_code, 4) << r.err.substr(0, 400);
    EXPECT_THAT(r.err, HasSubstr(forged.string() + ": expected " + key + " to hold JSON: it "
                                 "nests arrays and objects deeper than the limit of 128 levels"));
    EXPECT_LT(r.err.size(), 1000u);  // the value is not quoted back
  }
}

INSTANTIATE_TEST_SUITE_P(Keys, DeepKeyValue,
                         testing::Values("skybake.product", "skybake.channels", "skybake.zz"),
                         [](const auto& info) { return info.param.substr(8); });

// A value nested within the limit but of no metadata shape is quoted only as
// a short excerpt.
TEST(ShallowKeyValue, WrongShapeIsQuotedShort) {
  const fs::path dir = skybake::test::test_dir("cli_wide_kv");
  const fs::path file = baked_ktx2(dir);
  std::string wide = "[";
  for (int i = 0; i < 100000; ++i) wide += i ? ",[1]" : "[1]";
  wide += "]";
  skybake::test::write_bytes(file, skybake::test::with_ktx2_key_value(
                                       skybake::test::read_bytes(file), "skybake.product",
                                       wide + '\0'));
  const auto r = run_skybake({"info", file.string()});
  EXPECT_EQ(r.exit_code, 4) << r.err.substr(0, 400);
  EXPECT_THAT(r.err, HasSubstr("key/value 'skybake.product': expected"));
  EXPECT_LT(r.err.size(), 1000u);
  // A key of 100,000 bytes is cut too.
  const std::string long_key = "skybake." + std::string(100000, 'k');
  skybake::test::write_bytes(file, skybake::test::with_ktx2_key_value(
                                       skybake::test::read_bytes(file), long_key, "[[1]]" +
                                       std::string(1, '\0')));
  const auto l = run_skybake({"info", file.string()});
  EXPECT_EQ(l.exit_code, 4) << l.err.substr(0, 400);
  EXPECT_THAT(l.err, HasSubstr("key/value 'skybake.kkk"));
  EXPECT_LT(l.err.size(), 1000u);
}

}  // namespace

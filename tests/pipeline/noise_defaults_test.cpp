// A noise output that writes only its size: a default octave too fine for
// that size is named as the default, with what to write instead, and what
// the message says to write loads (pipeline/noise_products.cpp; the limit,
// at least 2 voxels per cell of the finest octave, is docs/reference.md
// "Cloud noise").
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

fs::path write_scene(const fs::path& dir, const std::string& name, const json& output) {
  const json scene = {{"name", name}, {"outputs", json::array({output})}};
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << scene.dump(2);
  return file;
}

std::vector<PresetProblem> problems_of(const fs::path& file) {
  try {
    load_scene(file);
  } catch (const PresetError& e) {
    return e.problems();
  }
  return {};
}

TEST(NoiseDefaults, ADefaultThatDoesNotFitTheSizeIsNamedWithWhatFits) {
  const fs::path dir = test::fresh_dir("noise_defaults");
  const json shape = {{"product", "noise_shape"}, {"size", {64, 64, 64}}};
  const std::vector<PresetProblem> problems = problems_of(write_scene(dir, "shape", shape));
  // Defaults G, B, A: (8, 3), (16, 3), (32, 2); at 64 the finest period is at most 32.
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].pointer, "/outputs/0/worley/1");
  EXPECT_EQ(problems[0].rule,
            "the default worley[1] (period 16, octaves 3: finest period 64) does not fit size 64, "
            "whose finest period is at most 32: write it as {\"period\": 16, \"octaves\": 2} (an "
            "entry of \"worley\" left {} keeps its default), or a size of at least 128");
  EXPECT_EQ(problems[1].pointer, "/outputs/0/worley/2");
  EXPECT_NE(problems[1].rule.find("write it as {\"period\": 32, \"octaves\": 1}"), std::string::npos)
      << problems[1].rule;

  // What the messages say to write loads.
  json fixed = shape;
  fixed["worley"] = json::array({json::object(), {{"period", 16}, {"octaves", 2}},
                                 {{"period", 32}, {"octaves", 1}}});
  EXPECT_TRUE(problems_of(write_scene(dir, "fixed", fixed)).empty());
  // So does the size they name.
  json larger = shape;
  larger["size"] = {128, 128, 128};
  EXPECT_TRUE(problems_of(write_scene(dir, "larger", larger)).empty());
}

// A value other than the default keeps the rule it breaks (a default is told
// by its value: the schema fills defaults in before the check).
TEST(NoiseDefaults, AWrittenValueKeepsTheRuleItBreaks) {
  const fs::path dir = test::fresh_dir("noise_defaults_written");
  const json shape = {{"product", "noise_shape"},
                      {"size", {64, 64, 64}},
                      {"worley", json::array({json::object(), {{"period", 8}, {"octaves", 4}},
                                              {{"period", 32}, {"octaves", 1}}})}};
  const std::vector<PresetProblem> problems = problems_of(write_scene(dir, "shape", shape));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].pointer, "/outputs/0/worley/1");
  EXPECT_EQ(problems[0].rule.rfind("expected the finest octave period", 0), 0u) << problems[0].rule;
}

TEST(NoiseDefaults, DetailAndCurlDefaultsSayTheSame) {
  const fs::path dir = test::fresh_dir("noise_defaults_detail");
  // Detail defaults R, G, B: (2, 3), (4, 3), (8, 2): at 16 the finest period is at most 8.
  const std::vector<PresetProblem> detail = problems_of(
      write_scene(dir, "detail", {{"product", "noise_detail"}, {"size", {16, 16, 16}}}));
  ASSERT_FALSE(detail.empty());
  EXPECT_EQ(detail[0].pointer, "/outputs/0/worley/1");
  EXPECT_NE(detail[0].rule.find("the default worley[1] (period 4, octaves 3: finest period 16)"),
            std::string::npos)
      << detail[0].rule;
  EXPECT_NE(detail[0].rule.find("write it as {\"period\": 4, \"octaves\": 2}"), std::string::npos)
      << detail[0].rule;
  const std::vector<PresetProblem> curl =
      problems_of(write_scene(dir, "curl", {{"product", "curl"}, {"size", {8, 8}}}));
  ASSERT_EQ(curl.size(), 1u);
  EXPECT_EQ(curl[0].pointer, "/outputs/0/octaves");
  EXPECT_NE(curl[0].rule.find("the default fBm"), std::string::npos) << curl[0].rule;
}

}  // namespace
}  // namespace skybake

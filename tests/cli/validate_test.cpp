// skybake validate end to end: every preset kind is checked by its $schema
// (scene, planet, atmosphere, clouds) against its schema and semantic rules;
// every problem of a file is listed (the first 20, then "and N more"); keys
// that have no effect are warnings on stderr (exit 0) and errors under
// --strict (exit 1), in --json too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using skybake::test::fresh_dir;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

std::string write(const fs::path& dir, const std::string& name, const json& doc) {
  const fs::path file = dir / name;
  std::ofstream(file) << doc.dump(2);
  return file.string();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  for (size_t start = 0, end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    out.push_back(text.substr(start, end - start));
  return out;
}

TEST(Validate, AcceptsEveryShippedPresetOfEveryKindWithoutWarnings) {
  std::vector<std::string> args = {"validate", "--strict", "--json"};
  for (const std::string dir :
       {"presets", "presets/clouds", "presets/atmospheres", "presets/extreme"})
    for (const auto& e : fs::directory_iterator(source_path(dir)))
      if (e.path().extension() == ".json") args.push_back(e.path().string());
  const auto r = run_skybake(args);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err, "");
  std::map<std::string, int> kinds;
  const json j = json::parse(r.out);
  for (const json& p : j["presets"]) {
    EXPECT_TRUE(p["valid"].get<bool>()) << p;
    EXPECT_TRUE(p["warnings"].empty()) << p;
    ++kinds[p["kind"].get<std::string>()];
  }
  EXPECT_GE(kinds["scene"], 6);
  EXPECT_EQ(kinds["clouds"], 4) << "clear, fair_weather_cumulus, overcast_stratus, storm";
  EXPECT_EQ(kinds["atmosphere"], 3) << "earth, earth_spectral, mars";
}

TEST(Validate, CloudsPresetsValidateByTheirSchema) {
  const auto r = run_skybake({"validate", source_path("presets/clouds/storm.json").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(clouds preset)"), std::string::npos) << r.out;
}

TEST(Validate, EachKindGetsItsSemanticRules) {
  const fs::path dir = fresh_dir("validate_kinds");
  // Clouds: a density ramp out of order, a rule the schema cannot say.
  const std::string clouds =
      write(dir, "clouds.json",
            {{"$schema", "../schemas/clouds.schema.json"},
             {"cloud_types", {{"stratus", {{"density", {0.05, 0.02, 0.09, 0.11}}}}}}});
  auto r = run_skybake({"validate", clouds});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(clouds + ": /cloud_types/stratus/density: expected a < b <= c < d"),
            std::string::npos)
      << r.err;
  // Atmosphere: two extra components, each with its own problem.
  const json extra = {{{"name", "dust"},
                       {"scattering_per_m", {1e-6, 1e-6, 1e-6}},
                       {"density", {{"exponential", {{"scale_height_km", 2}}}}}},
                      {{"name", "dust"},
                       {"absorption_per_m", {1e-6, 1e-6, 1e-6}},
                       {"density", {{"exponential", {{"scale_height_km", 2}}}}}}};
  const std::string atmosphere =
      write(dir, "atmosphere.json",
            {{"$schema", "atmosphere.schema.json"}, {"top_radius_km", 6460}, {"extra", extra}});
  r = run_skybake({"validate", atmosphere});
  EXPECT_EQ(r.exit_code, 1);
  ASSERT_EQ(lines(r.err).size(), 2u) << r.err;
  EXPECT_NE(lines(r.err)[0].find("/extra/0/phase: a component that scatters needs a phase"),
            std::string::npos)
      << r.err;
  EXPECT_NE(lines(r.err)[1].find("/extra/1/name: component name 'dust' is already used"),
            std::string::npos)
      << r.err;
  // Planet: its schema.
  const std::string planet =
      write(dir, "planet.json", {{"$schema", "planet.schema.json"}, {"radius_km", -1}});
  r = run_skybake({"validate", planet});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(planet + ": /radius_km: must be >"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("got -1"), std::string::npos) << r.err;
  // A $schema that is none of ours.
  const std::string other =
      write(dir, "other.json", {{"$schema", "../schemas/products/transmittance.schema.json"}});
  r = run_skybake({"validate", other});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(other + ": /$schema: expected the schema of a skybake preset"),
            std::string::npos)
      << r.err;
}

TEST(Validate, ListsTwentyProblemsAndCountsTheRest) {
  const fs::path dir = fresh_dir("validate_cap");
  json outputs = json::array();
  for (int i = 0; i < 25; ++i) outputs.push_back({{"product", "nothing" + std::to_string(i)}});
  const std::string file = write(dir, "many.json", {{"name", "many"}, {"outputs", outputs}});
  for (const bool bake : {false, true}) {
    const auto r = bake ? run_skybake({"bake", file, "-o", (dir / "out").string()})
                        : run_skybake({"validate", file});
    EXPECT_EQ(r.exit_code, bake ? 3 : 1);
    const std::vector<std::string> l = lines(r.err);
    ASSERT_EQ(l.size(), 21u) << r.err;
    EXPECT_EQ(l[0].rfind("skybake: error: " + file + ": /outputs/0/product: unknown product", 0),
              0u)
        << l[0];
    EXPECT_EQ(l[19].rfind("  " + file + ": /outputs/19/product: unknown product", 0), 0u) << l[19];
    EXPECT_EQ(l[20], "  and 5 more");
  }
  const json j = json::parse(run_skybake({"validate", "--json", file}).out);
  EXPECT_EQ(j["presets"][0]["problems"].size(), 25u);
}

TEST(Validate, KeysWithNoEffectAreWarningsAndErrorsUnderStrict) {
  const fs::path dir = fresh_dir("validate_warnings");
  const std::string file =
      write(dir, "warn.json",
            {{"name", "warn"},
             {"planet", {{"radius_km", 6360}}},
             {"atmosphere", {{"top_radius_km", 6460}}},
             {"clouds", json::object()},
             {"outputs",
              {{{"product", "transmittance"}, {"formats", {"png"}}, {"precision", "half"}},
               {{"product", "scattering"}, {"max_orders", 50}, {"tail", "none"}},
               {{"product", "scattering3d"}, {"tolerance", 0.01}, {"orders", 8}},
               {{"product", "curl"}, {"formats", {"exr"}}, {"mips", false}}}}});
  const std::vector<std::string> expected = {
      file + ": /clouds: has no effect: no output reads the clouds section",
      file +
          ": /outputs/0/precision: has no effect: precision sets EXR channels and DDS float "
          "formats, and this output writes only png",
      file +
          ": /outputs/1/max_orders: has no effect: max_orders applies when orders run until "
          "they converge (tolerance > 0)",
      file + ": /outputs/1/tail: has no effect: tail applies when orders run until they converge",
      file +
          ": /outputs/2/orders: has no effect: with tolerance > 0 orders run until they "
          "converge",
      file + ": /outputs/3/mips: has no effect: mips are the DDS mip chain"};

  auto r = run_skybake({"validate", file});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> l = lines(r.err);
  ASSERT_EQ(l.size(), expected.size()) << r.err;
  for (size_t i = 0; i < l.size(); ++i)
    EXPECT_EQ(l[i].rfind("skybake: warning: " + expected[i], 0), 0u) << l[i];
  EXPECT_NE(r.out.find("ok      " + file), std::string::npos);

  r = run_skybake({"validate", "--strict", file});
  EXPECT_EQ(r.exit_code, 1);
  l = lines(r.err);
  ASSERT_EQ(l.size(), expected.size()) << r.err;
  EXPECT_EQ(l[0].rfind("skybake: error: " + expected[0], 0), 0u) << l[0];
  for (size_t i = 1; i < l.size(); ++i) EXPECT_EQ(l[i].rfind("  " + expected[i], 0), 0u) << l[i];

  const json j = json::parse(run_skybake({"validate", "--json", file}).out)["presets"][0];
  EXPECT_TRUE(j["valid"].get<bool>());
  ASSERT_EQ(j["warnings"].size(), expected.size());
  EXPECT_EQ(j["warnings"][1]["pointer"], "/outputs/0/precision");
  const json strict =
      json::parse(run_skybake({"validate", "--json", "--strict", file}).out)["presets"][0];
  EXPECT_FALSE(strict["valid"].get<bool>());
  EXPECT_EQ(strict["problems"].size(), expected.size());

  // The same keys where they do act: no warning.
  const std::string fine =
      write(dir, "fine.json",
            {{"name", "fine"},
             {"planet", {{"radius_km", 6360}}},
             {"atmosphere", {{"top_radius_km", 6460}}},
             {"outputs",
              {{{"product", "transmittance"}, {"formats", {"exr", "png"}}, {"precision", "half"}},
               {{"product", "scattering"}, {"tolerance", 0.01}, {"max_orders", 50}}}}});
  r = run_skybake({"validate", "--strict", fine});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// One rule for keys that change nothing: a format's keys without the format
// and max_error on a product whose error is not measured warn like mips
// without DDS, rather than fail (docs/presets.md "Keys that have no effect").
TEST(Validate, FormatKeysWithoutTheirFormatWarnLikeEveryKeyWithNoEffect) {
  const fs::path dir = fresh_dir("validate_format_keys");
  const std::string file = write(
      dir, "keys.json",
      {{"name", "keys"},
       {"planet", {{"radius_km", 6360}}},
       {"atmosphere", {{"top_radius_km", 6460}}},
       {"clouds", json::object()},
       {"outputs",
        {{{"product", "transmittance"},
          {"formats", {"png"}},
          {"exr_compression", "zip"},
          {"dds_format", "R16G16B16A16_FLOAT"},
          {"dds_header", "dx10"},
          {"ktx2_format", "R16G16B16A16_SFLOAT"},
          {"max_error", 0.5}},
         {{"product", "noise_detail"},
          {"formats", {"dds"}},
          {"grid_names", {"a", "b"}},  // not one per channel, but no VDB is written
          {"vdb_compression", "zip"}},
         {{"product", "weather"}, {"size", {64, 64}}, {"formats", {"dds"}}, {"max_error", 0.1}}}}});
  const std::vector<std::string> expected = {
      "/outputs/0/exr_compression: has no effect: exr_compression is only used with \"exr\" in "
      "formats, and this output writes png",
      "/outputs/0/dds_format: has no effect: dds_format is only used with \"dds\"",
      "/outputs/0/dds_header: has no effect: dds_header is only used with \"dds\"",
      "/outputs/0/ktx2_format: has no effect: ktx2_format is only used with \"ktx2\"",
      "/outputs/1/grid_names: has no effect: grid_names is only used with \"vdb\"",
      "/outputs/1/vdb_compression: has no effect: vdb_compression is only used with \"vdb\"",
      "/outputs/2/max_error: has no effect: the bake measures no error of weather"};
  auto r = run_skybake({"validate", file});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> l = lines(r.err);
  ASSERT_EQ(l.size(), expected.size()) << r.err;
  for (size_t i = 0; i < l.size(); ++i)
    EXPECT_EQ(l[i].rfind("skybake: warning: " + file + ": " + expected[i], 0), 0u) << l[i];
  r = run_skybake({"validate", "--strict", file});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("skybake: error: " + file + ": " + expected[0], 0), 0u) << r.err;
}

// Folders and globs, as bake takes them: a folder's scene presets,
// recursively, and what a pattern matches (docs/presets.md).
TEST(Validate, AcceptsFoldersAndGlobsAsBakeDoes) {
  const skybake::test::RunResult folder = run_skybake({"validate", source_path("presets").string()});
  EXPECT_EQ(folder.exit_code, 0) << folder.err;
  EXPECT_NE(folder.out.find("earth.json (scene 'earth'"), std::string::npos) << folder.out;
  EXPECT_NE(folder.out.find("extreme/"), std::string::npos) << folder.out;
  EXPECT_EQ(folder.out.find("atmospheres/earth.json"), std::string::npos)
      << "a folder expands to its scene presets: " << folder.out;
  const skybake::test::RunResult glob =
      run_skybake({"validate", source_path("presets").string() + "/earth*.json"});
  EXPECT_EQ(glob.exit_code, 0) << glob.err;
  size_t earth_presets = 0;  // what the pattern matches, counted here
  for (const auto& e : fs::directory_iterator(source_path("presets"))) {
    const std::string name = e.path().filename().string();
    earth_presets += name.rfind("earth", 0) == 0 && e.path().extension() == ".json";
  }
  EXPECT_GE(earth_presets, 4u);
  EXPECT_EQ(lines(glob.out).size(), earth_presets) << glob.out;
  const fs::path dir = fresh_dir("validate_nothing");
  const skybake::test::RunResult none = run_skybake({"validate", (dir / "*.json").string()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("no such preset file, folder or matching pattern"), std::string::npos);
}

}  // namespace

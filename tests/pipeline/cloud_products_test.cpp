// Cloud texture products end to end: the shipped storm scene bakes
// every file, the weather map and cirrus DDS tile (check-tiling), the rain
// rule and the mean coverage hold on the written files, the schema defaults
// are the documented profiles, the Frostbite layout indexes the cumulonimbus
// column where it rains, editing the clouds section re-bakes, inline and
// referenced clouds hash the same, and threads do not change a byte.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "clouds/cloud_types.hpp"
#include "io/dds.hpp"
#include "io/exr.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

const std::string kStorm = test::source_path("presets/earth_storm.json").string();

json read_json(const fs::path& p) {
  return json::parse(test::read_file(p));
}

fs::path baked_storm() {
  static const fs::path out = [] {
    const fs::path dir = test::fresh_dir("cloud_products");
    const auto r = test::run_skybake({"bake", kStorm, "-o", dir.string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir / "earth_storm";
  }();
  return out;
}

// A scene in `dir` with the given clouds section and outputs.
fs::path write_scene(const fs::path& dir, const std::string& name, const json& clouds,
                     const json& outputs) {
  const json scene = {{"name", name}, {"clouds", clouds}, {"outputs", outputs}};
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << scene.dump(2);
  return file;
}

// The storm clouds preset without the keys that are not part of the section.
json storm_clouds_inline() {
  json c = read_json(test::source_path("presets/clouds/storm.json"));
  c.erase("$schema");
  c.erase("description");
  return c;
}

TEST(CloudProducts, StormSceneWritesEveryFile) {
  const auto files = test::list_files(baked_storm());
  for (const std::string f :
       {"weather.dds", "weather.exr", "weather.preview.png", "cloud_types.dds", "cloud_types.exr",
        "cloud_types.preview.png", "height_gradients.dds", "height_gradients.exr", "cirrus.dds",
        "cirrus.preview.png", "transmittance.exr", "manifest.json"})
    EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f;
}

TEST(CloudProducts, WeatherAndCirrusDdsTile) {
  const fs::path dir = baked_storm();
  const auto r = test::run_skybake({"check-tiling", "--json", (dir / "weather.dds").string(),
                                    (dir / "cirrus.dds").string(), (dir / "weather.exr").string()});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(json::parse(r.out)["tiles"].get<bool>()) << r.out;
}

TEST(CloudProducts, WeatherDdsIsUnorm8WithATilingMipChain) {
  const DdsImage dds = read_dds((baked_storm() / "weather.dds").string());
  EXPECT_EQ(dds.format, DdsFormat::R8G8B8A8_UNORM);
  EXPECT_EQ(dds.mips.size(), 10u) << "512 -> 1";
}

TEST(CloudProducts, RainRuleAndMeanCoverageHoldOnTheWrittenFiles) {
  const json weather = read_json(test::source_path("presets/clouds/storm.json"))["weather"];
  const double coverage = weather["coverage"]["mean"].get<double>();
  const Texture exr = read_exr((baked_storm() / "weather.exr").string());
  const Texture dds = read_dds((baked_storm() / "weather.dds").string()).mips[0];
  ASSERT_EQ(exr.channel_count(), 3);
  double sum = 0.0, sum8 = 0.0;
  size_t raining = 0;
  for (size_t i = 0; i < exr.texel_count(); ++i) {
    const float* v = &exr.data[i * 3];
    const float* q = &dds.data[i * dds.channel_count()];
    sum += v[0];
    sum8 += q[0];
    if (v[1] == 1.0f) {
      ++raining;
      ASSERT_GE(v[0], 0.7f);
      ASSERT_EQ(v[2], 1.0f);
    }
    if (q[1] == 1.0f) {  // unorm8: exact up to half a step (0.7 encodes as 178 / 255)
      ASSERT_GE(q[0], 0.7f - 0.5f / 255.0f);
      ASSERT_EQ(q[2], 1.0f);
    }
  }
  EXPECT_NEAR(sum / exr.texel_count(), coverage, 1e-5);
  EXPECT_NEAR(sum8 / dds.texel_count(), coverage, 0.5 / 255.0);
  const double area = weather["precipitation"]["area"].get<double>();
  EXPECT_EQ(raining, size_t(std::lround(area * exr.texel_count())));
  EXPECT_EQ(meta_double(exr.metadata, "world_size_km"), 60.0);
}

TEST(CloudProducts, SchemaDefaultsAreTheDocumentedProfiles) {
  const fs::path dir = test::fresh_dir("cloud_defaults");
  const fs::path scene = write_scene(dir, "defaults", json::object(),
                                     {{{"product", "cloud_types"}, {"formats", {"exr"}}}});
  ASSERT_EQ(test::run_skybake({"bake", scene.string(), "-o", dir.string(), "-q"}).exit_code, 0);
  const Texture baked = read_exr((dir / "defaults" / "cloud_types.exr").string());
  const Texture expected = bake_cloud_types(CloudTypesSpec{});  // default_cloud_types()
  ASSERT_EQ(baked.width, 4);
  ASSERT_EQ(baked.height, 128);
  EXPECT_TRUE(baked.data == expected.data);
  EXPECT_EQ(meta_string(baked.metadata, "type.3"), "cumulonimbus");
}

TEST(CloudProducts, FrostbiteLayoutPointsAtTheCumulonimbusColumnWhereItRains) {
  const fs::path dir = test::fresh_dir("cloud_frostbite");
  const json outputs = {{{"product", "weather"}, {"size", {128, 128}}, {"formats", {"exr"}}}};
  json frost = outputs;
  frost[0]["layout"] = "frostbite";
  const fs::path a = write_scene(dir, "schneider", storm_clouds_inline(), outputs);
  const fs::path b = write_scene(dir, "frostbite", storm_clouds_inline(), frost);
  ASSERT_EQ(test::run_skybake({"bake", a.string(), b.string(), "-o", dir.string(), "-q"}).exit_code,
            0);
  const Texture s = read_exr((dir / "schneider" / "weather.exr").string());
  const Texture f = read_exr((dir / "frostbite" / "weather.exr").string());
  ASSERT_EQ(f.channel_count(), 2);
  // storm.json adds one type ("anvil"): five columns, cumulonimbus is column 3.
  EXPECT_EQ(meta_int(f.metadata, "type_count"), 5);
  size_t raining = 0;
  for (size_t i = 0; i < s.texel_count(); ++i) {
    EXPECT_EQ(f.data[i * 2], s.data[i * 3]);
    if (s.data[i * 3 + 1] == 1.0f) {
      ++raining;
      ASSERT_EQ(f.data[i * 2 + 1], float(3.5 / 5));
    }
  }
  EXPECT_GT(raining, 0u);
}

TEST(CloudProducts, EditingTheCloudsSectionRebakesAndInlineEqualsReferenced) {
  const fs::path dir = test::fresh_dir("cloud_rebake");
  fs::copy_file(test::source_path("presets/clouds/storm.json"), dir / "storm.json");
  const json outputs = {{{"product", "cirrus"}, {"size", {64, 64}}, {"formats", {"dds"}}}};
  const fs::path referenced = write_scene(dir, "referenced", "storm.json", outputs);
  const fs::path inlined = write_scene(dir, "inlined", storm_clouds_inline(), outputs);
  auto bake = [&](const fs::path& scene) {
    const auto r = test::run_skybake({"bake", scene.string(), "-o", dir.string(), "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out)["scenes"][0]["outputs"][0];
  };
  const json first = bake(referenced);
  EXPECT_EQ(first["status"], "baked");
  EXPECT_EQ(bake(inlined)["input_hash"], first["input_hash"]);
  EXPECT_EQ(bake(referenced)["status"], "up to date");
  json clouds = read_json(dir / "storm.json");
  clouds["seed"] = 8;
  std::ofstream(dir / "storm.json") << clouds.dump();
  const json edited = bake(referenced);
  EXPECT_EQ(edited["status"], "baked");
  EXPECT_NE(edited["input_hash"], first["input_hash"]);
}

// A seed is an int wherever a person reads it: the manifest's JSON integer,
// `skybake info`; the schemas keep it within what an int holds.
TEST(CloudProducts, SeedIsAnIntegerInTheManifestAndInfo) {
  const fs::path dir = test::fresh_dir("cloud_seed");
  json clouds = storm_clouds_inline();
  clouds["seed"] = 2147483647;
  const fs::path scene =
      write_scene(dir, "seed", clouds, {{{"product", "cirrus"}, {"size", {64, 64}}, {"formats", {"exr"}}}});
  const auto r = test::run_skybake({"bake", scene.string(), "-o", dir.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json manifest = read_json(dir / "seed" / "manifest.json");
  const json& seed = manifest["outputs"][0]["metadata"]["seed"];
  EXPECT_TRUE(seed.is_number_integer()) << seed.dump();
  EXPECT_EQ(seed.get<int64_t>(), 2147483647);
  const auto info = test::run_skybake({"info", (dir / "seed" / "cirrus.exr").string()});
  EXPECT_NE(info.out.find("seed"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find(" 2147483647\n"), std::string::npos) << info.out;
  clouds["seed"] = 2147483648LL;
  const fs::path big = write_scene(dir, "big", clouds, {{{"product", "cirrus"}}});
  const auto refused = test::run_skybake({"validate", big.string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("/clouds/seed: must be <= 2147483647"), std::string::npos) << refused.err;
}

TEST(CloudProducts, RampOutOfOrderIsRefusedWithItsPointerAndNothingWritten) {
  const fs::path dir = test::fresh_dir("cloud_bad_ramp");
  const json clouds = {{"cloud_types", {{"stratus", {{"density", {0.05, 0.02, 0.09, 0.11}}}}}}};
  const fs::path scene = write_scene(dir, "bad", clouds, {{{"product", "cloud_types"}}});
  const auto r = test::run_skybake({"bake", scene.string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("/clouds/cloud_types/stratus/density: expected a < b <= c < d"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(test::list_files(dir / "out").empty());
}

TEST(CloudProducts, ByteIdenticalForOneAndTwoThreads) {
  // The storm clouds at 256^2 (the shipped 512^2 scene takes twice as long).
  const fs::path dir = test::fresh_dir("cloud_threads");
  const json outputs = {{{"product", "weather"}, {"size", {256, 256}}},
                        {{"product", "cloud_types"}},
                        {{"product", "cirrus"}, {"size", {256, 256}}}};
  const fs::path scene =
      write_scene(dir, "storm", test::source_path("presets/clouds/storm.json").string(), outputs);
  const fs::path one = dir / "one", two = dir / "two";
  for (const auto& [out, threads] : {std::pair{one, "1"}, std::pair{two, "2"}})
    ASSERT_EQ(
        test::run_skybake({"bake", scene.string(), "-o", out.string(), "-q", "--threads", threads})
            .exit_code,
        0);
  for (const std::string f :
       {"weather.dds", "weather.exr", "weather.preview.png", "cloud_types.dds", "cloud_types.exr",
        "cirrus.dds", "cirrus.exr", "cirrus.preview.png"})
    EXPECT_TRUE(test::read_file(one / "storm" / f) == test::read_file(two / "storm" / f)) << f;
}

}  // namespace
}  // namespace skybake

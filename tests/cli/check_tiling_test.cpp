// skybake check-tiling end to end: every shipped noise and cloud template
// product tiles in every file it writes; each seam a person would see gives
// exit 1 (a ramp in one mip level, the last x-plane of a noise volume raised
// by 40/255, a crop across the cirrus fibres, a cropped EXR that keeps
// skybake's attributes), white noise cannot tell (exit 1), and only a file
// that cannot be read exits 4.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "io/dds.hpp"
#include "io/exr.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

// Bakes `scene` (written to DIR/<name>.json) into DIR/out; returns DIR/out/<scene name>.
fs::path bake_scene_json(const fs::path& dir, const json& scene,
                         const std::vector<std::string>& extra = {}) {
  const fs::path file = dir / (scene["name"].get<std::string>() + ".json");
  std::ofstream(file) << scene.dump(2);
  std::vector<std::string> args = {"bake", file.string(), "-o", (dir / "out").string(), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::run_skybake(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir / "out" / scene["name"].get<std::string>();
}

fs::path baked_noise() {
  static const fs::path dir = [] {
    const fs::path out = test::fresh_dir("check_tiling_noise");
    const auto r = test::run_skybake(
        {"bake", test::source_path("presets/clouds/horizon_zero_dawn.json").string(),
         test::source_path("presets/clouds/frostbite_packed.json").string(), "-o", out.string(),
         "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }();
  return dir;
}

// The tiling files of a baked folder (EXR, DDS, VDB).
std::vector<std::string> texture_files(const fs::path& dir) {
  std::vector<std::string> files;
  for (const std::string& f : test::list_files(dir)) {
    const std::string ext = fs::path(f).extension().string();
    if (ext == ".exr" || ext == ".dds" || ext == ".vdb") files.push_back((dir / f).string());
  }
  return files;
}

test::RunResult check(std::vector<std::string> files, bool as_json = false) {
  files.insert(files.begin(), "check-tiling");
  if (as_json) files.insert(files.begin() + 1, "--json");
  return test::run_skybake(files);
}

// The entry of check-tiling's JSON for one file, level, axis and channel.
json entry(const json& file, int level, const std::string& axis, const std::string& channel) {
  for (const json& a : file["axes"])
    if (a["level"] == level && a["axis"] == axis && a["channel"] == channel) return a;
  return json();
}

TEST(CheckTiling, ShippedNoisePresetsTileInEveryFile) {
  std::vector<std::string> files;
  for (const char* scene : {"clouds_hzd", "clouds_frostbite_packed"})
    for (const std::string& f : texture_files(baked_noise() / scene)) files.push_back(f);
  ASSERT_EQ(files.size(), 10u) << "hzd: 3 dds, 2 vdb, 3 exr; frostbite: 2 dds";
  const auto r = check(files, true);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["verdict"], "tiles");
  for (const json& f : j["files"]) {
    EXPECT_EQ(f["verdict"], "tiles") << f["file"];
    if (fs::path(f["file"].get<std::string>()).extension() == ".dds") {
      EXPECT_GT(f["mip_levels"].get<int>(), 1) << "every mip level is checked: " << f["file"];
    }
  }
}

// A folder and a pattern stand for the texture files they hold, as bake's
// preset arguments do: the same files, measured the same.
TEST(CheckTiling, FoldersAndPatternsAreTheirTextureFiles) {
  const fs::path dir = baked_noise() / "clouds_hzd";
  std::vector<std::string> named = texture_files(dir);
  for (const std::string& f : test::list_files(dir))
    if (fs::path(f).extension() == ".ktx2") named.push_back((dir / f).string());
  std::sort(named.begin(), named.end());
  ASSERT_FALSE(named.empty());
  const auto listed = [](const test::RunResult& r) {
    const json out = json::parse(r.out);
    std::vector<std::string> files;
    for (const json& f : out["files"]) files.push_back(f["file"].get<std::string>());
    return files;
  };
  const auto folder = check({dir.string()}, true);
  EXPECT_EQ(folder.exit_code, 0) << folder.err;
  EXPECT_EQ(listed(folder), named);
  const auto pattern = check({(dir / "*.dds").string()}, true);
  EXPECT_EQ(pattern.exit_code, 0) << pattern.err;
  for (const std::string& f : listed(pattern)) EXPECT_EQ(fs::path(f).extension(), ".dds") << f;
  const auto info = test::run_skybake({"info", "--json", dir.string()});
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(listed(info), named);
  const auto none = check({(dir / "*.nothing").string()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
}

TEST(CheckTiling, ShippedCloudsPresetsTileInEveryFile) {
  const fs::path dir = test::fresh_dir("check_tiling_clouds");
  std::vector<std::string> files;
  for (const std::string preset : {"clear", "fair_weather_cumulus", "overcast_stratus", "storm"}) {
    // Weather at 256^2 (and the Frostbite layout for one); cirrus at its
    // default 512^2: at 256 rows its streaks are too thin across the fibres
    // for a seam to show (cannot tell).
    const json scene = {
        {"name", preset},
        {"clouds", test::source_path("presets/clouds/" + preset + ".json").string()},
        {"outputs",
         {{{"product", "weather"},
           {"size", {256, 256}},
           {"formats", {"dds", "exr"}},
           {"layout", preset == "storm" ? "frostbite" : "schneider"}},
          {{"product", "cirrus"}, {"size", {512, 512}}, {"formats", {"dds", "exr"}}}}}};
    for (const std::string& f : texture_files(bake_scene_json(dir, scene))) files.push_back(f);
  }
  // The shipped scenes at their own sizes (512^2).
  for (const char* preset : {"presets/earth_storm.json", "presets/earth_fair_weather.json"}) {
    const auto r = test::run_skybake({"bake", test::source_path(preset).string(), "-o",
                                      (dir / "scenes").string(), "-q", "--only", "weather,cirrus"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const std::string& f : texture_files(dir / "scenes")) files.push_back(f);
  ASSERT_GE(files.size(), 20u);
  const auto r = check(files, true);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  const json j = json::parse(r.out);
  for (const json& f : j["files"])
    EXPECT_EQ(f["verdict"], "tiles") << f["file"] << " worst " << f["worst_ratio"];
}

TEST(CheckTiling, AMipLevelReplacedByARampFails) {
  const fs::path dir = test::fresh_dir("check_tiling_mip_ramp");
  DdsImage dds = read_dds((baked_noise() / "clouds_hzd/noise_shape.dds").string());
  ASSERT_EQ(dds.mips.size(), 8u);
  Texture& level1 = dds.mips[1];  // 64^3
  for (int z = 0; z < level1.depth; ++z)
    for (int y = 0; y < level1.height; ++y)
      for (int x = 0; x < level1.width; ++x)
        for (int c = 0; c < level1.channel_count(); ++c)
          level1.at(x, y, z, 0, c) = float(x) / float(level1.width);
  const std::string file = (dir / "ramp_mip.dds").string();
  write_dds(file, dds.mips, dds.format);
  const auto r = check({file});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_EQ(r.out.rfind("NO TILE", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("level 1  axis x  R       64 texels  values"), std::string::npos) << r.out;
  const json j = json::parse(check({file}, true).out)["files"][0];
  EXPECT_EQ(entry(j, 1, "x", "R")["verdict"], "seam");
  EXPECT_EQ(entry(j, 0, "x", "R")["verdict"], "tiles") << "level 0 is untouched";
}

TEST(CheckTiling, LastXPlaneRaisedByFortyLevelsFails) {
  const fs::path dir = test::fresh_dir("check_tiling_step");
  DdsImage dds = read_dds((baked_noise() / "clouds_hzd/noise_shape.dds").string());
  Texture& t = dds.mips[0];
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int c = 0; c < t.channel_count(); ++c) {
        float& v = t.at(t.width - 1, y, z, 0, c);
        v = std::min(1.0f, v + 40.0f / 255.0f);
      }
  const std::string file = (dir / "step.dds").string();
  write_dds(file, dds.mips, dds.format);
  const auto r = check({file}, true);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  const json j = json::parse(r.out)["files"][0];
  EXPECT_EQ(j["verdict"], "seam");
  for (const char* c : {"R", "G", "B", "A"}) {
    EXPECT_EQ(entry(j, 0, "x", c)["verdict"], "seam") << c;
    EXPECT_EQ(entry(j, 0, "y", c)["verdict"], "tiles") << c;
  }
}

TEST(CheckTiling, WhiteNoiseCannotTell) {
  const fs::path dir = test::fresh_dir("check_tiling_white");
  Texture t(128, 128, 1, 1, {"R", "G"});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& v : t.data) v = u(rng);
  const std::string file = (dir / "white.exr").string();
  write_exr(file, t, ExrPrecision::float32);
  const auto r = check({file});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_EQ(r.out.rfind("CANNOT TELL", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("too rough for a seam to show"), std::string::npos) << r.out;
  EXPECT_EQ(json::parse(check({file}, true).out)["verdict"], "cannot_tell");
}

TEST(CheckTiling, CirrusStreaksAcrossTheFibresTileAndACropShows) {
  // Cirrus R along y: neighbouring rows already differ by up to 1.0 (the
  // streaks are thin across their fibres), so a seam must be told from the
  // distribution of the interior faces, not from their largest jump.
  const fs::path dir = test::fresh_dir("check_tiling_cirrus");
  const json scene = {
      {"name", "cirrus"},
      {"clouds", test::source_path("presets/clouds/fair_weather_cumulus.json").string()},
      {"outputs", {{{"product", "cirrus"}, {"size", {512, 512}}, {"formats", {"exr"}}}}}};
  const Texture cirrus = read_exr((bake_scene_json(dir, scene) / "cirrus.exr").string());
  Texture streaks(512, 512, 1, 1, {"R"});
  float largest_jump = 0.0f;
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      streaks.at(x, y, 0, 0, 0) = cirrus.at(x, y, 0, 0, 0);
      if (y > 0)
        largest_jump = std::max(largest_jump,
                                std::abs(cirrus.at(x, y, 0, 0, 0) - cirrus.at(x, y - 1, 0, 0, 0)));
    }
  EXPECT_GT(largest_jump, 0.9f);
  const std::string whole = (dir / "streaks.exr").string();
  write_exr(whole, streaks, ExrPrecision::float32);
  EXPECT_EQ(check({whole}).exit_code, 0) << check({whole}).out;

  // Crop 32 rows (1.5 cells of the fibres' first octave): the wrap now
  // joins rows that were not neighbours.
  Texture cropped(512, 480, 1, 1, {"R"});
  std::copy(streaks.data.begin(), streaks.data.begin() + cropped.data.size(), cropped.data.begin());
  const std::string file = (dir / "streaks_cropped.exr").string();
  write_exr(file, cropped, ExrPrecision::float32);
  const auto r = check({file}, true);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  const json j = json::parse(r.out)["files"][0];
  EXPECT_EQ(entry(j, 0, "y", "R")["verdict"], "seam") << entry(j, 0, "y", "R");
  EXPECT_EQ(entry(j, 0, "x", "R")["verdict"], "tiles");
}

TEST(CheckTiling, CroppedExrKeepingSkybakeAttributesIsReadAndFails) {
  const fs::path dir = test::fresh_dir("check_tiling_cropped_exr");
  const json scene = {
      {"name", "weather"},
      {"clouds", test::source_path("presets/clouds/storm.json").string()},
      {"outputs", {{{"product", "weather"}, {"size", {256, 256}}, {"formats", {"exr"}}}}}};
  const std::string source = (bake_scene_json(dir, scene) / "weather.exr").string();
  // Another tool crops the picture to 200 columns and copies every header
  // attribute, skybake:shape "256x256x1x1" included.
  auto in = OIIO::ImageInput::open(source);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  in->close();
  OIIO::ImageSpec cropped_spec = spec;
  cropped_spec.width = cropped_spec.full_width = 200;
  EXPECT_EQ(cropped_spec.get_string_attribute("skybake:shape"), "256x256x1x1");
  std::vector<float> cropped(size_t(200) * spec.height * spec.nchannels);
  for (int y = 0; y < spec.height; ++y)
    std::copy_n(&pixels[size_t(y) * spec.width * spec.nchannels], 200 * spec.nchannels,
                &cropped[size_t(y) * 200 * spec.nchannels]);
  const std::string file = (dir / "weather_cropped.exr").string();
  auto out = OIIO::ImageOutput::create("openexr");
  ASSERT_TRUE(out && out->open(file, cropped_spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, cropped.data()));
  out->close();

  EXPECT_EQ(test::run_skybake({"info", file}).exit_code, 4) << "info reads what the file records";
  const auto r = check({file});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("NO TILE", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("note: measured as stored: "), std::string::npos) << r.out;
  const json j = json::parse(check({file}, true).out)["files"][0];
  EXPECT_EQ(j["shape"], "200x256");
  EXPECT_EQ(entry(j, 0, "x", "R")["verdict"], "seam");
  EXPECT_EQ(entry(j, 0, "y", "R")["verdict"], "tiles");
  EXPECT_TRUE(j.contains("note"));
}

TEST(CheckTiling, OnlyAnUnreadableFileExitsFour) {
  const fs::path dir = test::fresh_dir("check_tiling_unreadable");
  const std::string good = (baked_noise() / "clouds_hzd/curl.dds").string();
  const std::string bytes = test::read_file(good);
  const std::string truncated = (dir / "truncated.dds").string();
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string garbage = (dir / "garbage.exr").string();
  std::ofstream(garbage, std::ios::binary) << "not an exr at all";
  EXPECT_EQ(check({truncated}).exit_code, 4);
  EXPECT_EQ(check({garbage}).exit_code, 4);
  EXPECT_EQ(check({good}).exit_code, 0);
}

}  // namespace
}  // namespace skybake

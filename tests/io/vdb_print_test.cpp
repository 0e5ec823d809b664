// VDB conventions seen by another tool: vdb_print (Debian libopenvdb-tools)
// lists the grids of our files, so their names and class are what Blender
// and Houdini see; our reader still reads the files back exactly. The test
// fails when vdb_print is missing.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/vdb.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Grid name -> its "class" metadata line, from `vdb_print -m`; empty (with a
// test failure) when vdb_print cannot run.
std::map<std::string, std::string> grid_classes(const std::string& path) {
  std::map<std::string, std::string> classes;
  if (std::system("command -v vdb_print > /dev/null 2>&1") != 0) {
    ADD_FAILURE() << "vdb_print is not installed (apt-get install libopenvdb-tools)";
    return classes;
  }
  FILE* pipe = popen(("vdb_print -m '" + path + "' 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  EXPECT_EQ(pclose(pipe), 0) << out;
  // A grid's block starts with an unindented line "<name>  float ..."; its
  // metadata lines are indented ("   class: fog volume").
  std::string grid;
  size_t at = 0;
  while (at < out.size()) {
    const size_t end = std::min(out.find('\n', at), out.size());
    const std::string line = out.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line[0] != ' ') {
      grid = line.substr(0, line.find(' '));
      classes[grid];  // present, class unknown until a class line says otherwise
    } else if (!grid.empty() && line.rfind("   class: ", 0) == 0) {
      classes[grid] = line.substr(10);
    }
  }
  return classes;
}

Texture volume() {
  Texture tex(6, 5, 4, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(i % 13) / 12.0f;
  tex.metadata["product"] = "noise_shape";
  return tex;
}

TEST(VdbConventions, GridNamesAndFogVolumeClassAsVdbPrintSeesThem) {
  const std::string path = test::scratch_file("io_vdb_print", "names", "fog.vdb");
  const Texture tex = volume();
  VdbWriteOptions options;
  options.voxel_size = 1.0 / 6;
  options.grid_names = {"density", "G", "B", "A"};
  options.grid_class = VdbGridClass::fog_volume;
  write_vdb(path, tex, options);
  const std::map<std::string, std::string> classes = grid_classes(path);
  EXPECT_EQ(classes, (std::map<std::string, std::string>{{"A", "fog volume"},
                                                         {"B", "fog volume"},
                                                         {"G", "fog volume"},
                                                         {"density", "fog volume"}}));
  // Our reader maps the grids back to the texture's channels, in order.
  const Texture back = read_vdb(path);
  EXPECT_EQ(back.channels, tex.channels);
  EXPECT_EQ(back.data, tex.data);
  EXPECT_EQ(back.metadata, tex.metadata);
}

TEST(VdbConventions, WithoutOptionsGridsAreTheChannelsOfUnknownClass) {
  const std::string path = test::scratch_file("io_vdb_print", "plain", "plain.vdb");
  write_vdb(path, volume(), 0.5);
  const std::map<std::string, std::string> classes = grid_classes(path);
  ASSERT_EQ(classes.size(), 4u);
  for (const auto& [name, cls] : classes) {
    EXPECT_THAT(name, ::testing::AnyOf("R", "G", "B", "A"));
    EXPECT_THAT(cls, ::testing::AnyOf("", "unknown")) << name;
  }
}

TEST(VdbConventions, BadGridNamesAreRefusedBeforeAFileExists) {
  const std::string path = test::scratch_file("io_vdb_print", "refuse", "bad.vdb");
  const auto refusal = [&](std::vector<std::string> names) -> std::string {
    VdbWriteOptions options;
    options.grid_names = std::move(names);
    try {
      write_vdb(path, volume(), options);
    } catch (const IoError& e) {
      return e.what();
    }
    return "no refusal";
  };
  EXPECT_THAT(refusal({"density", "G"}),
              HasSubstr(path + ": expected one grid name per channel (4), got 2 (density, G)"));
  EXPECT_THAT(refusal({"density", "G", "B", "9a"}),
              HasSubstr("expected grid names of letters, digits and '_' (not starting with a "
                        "digit, at most 64), got '9a'"));
  EXPECT_THAT(refusal({"density", "G", "B", "a b"}), HasSubstr("got 'a b'"));
  EXPECT_THAT(refusal({"density", "G", "G", "A"}),
              HasSubstr("expected distinct grid names, got density, G, G, A"));
  EXPECT_FALSE(fs::exists(path));
}

// A scene of the two noise volumes in VDB, baked by the real skybake.
std::string bake_noise(const std::string& name, const std::string& detail_extra) {
  const fs::path dir = test::fresh_dir("vdb_print_" + name);
  std::ofstream(dir / "scene.json") << R"({"name": "n", "outputs": [
           {"product": "noise_shape", "size": [32, 32, 32], "formats": ["vdb"],
            "perlin": {"period": 4, "octaves": 2}, "perlin_worley": {"period": 4, "octaves": 2},
            "worley": [{"period": 4, "octaves": 2}, {"period": 8, "octaves": 2},
                       {"period": 8, "octaves": 2}]},
           {"product": "noise_detail", "size": [32, 32, 32], "formats": ["vdb"])"
                                    << detail_extra << "}]}";
  const auto r = test::run_skybake({"bake", "scene.json", "-o", "out", "--quiet"}, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return (dir / "out" / "n").string();
}

TEST(VdbConventions, BakedNoiseVolumesShowADensityFogVolume) {
  const std::string out = bake_noise("defaults", "");
  EXPECT_EQ(grid_classes(out + "/noise_shape.vdb"),
            (std::map<std::string, std::string>{{"A", "fog volume"},
                                                {"B", "fog volume"},
                                                {"G", "fog volume"},
                                                {"density", "fog volume"}}));
  EXPECT_EQ(grid_classes(out + "/noise_detail.vdb"),
            (std::map<std::string, std::string>{
                {"B", "fog volume"}, {"G", "fog volume"}, {"density", "fog volume"}}));
  EXPECT_EQ(read_vdb(out + "/noise_detail.vdb").channels,
            (std::vector<std::string>{"R", "G", "B"}));
}

TEST(VdbConventions, BakedGridNamesFollowThePreset) {
  const std::string out =
      bake_noise("named", R"(, "grid_names": ["cloud_detail", "detail_g", "detail_b"])");
  EXPECT_EQ(
      grid_classes(out + "/noise_detail.vdb"),
      (std::map<std::string, std::string>{
          {"cloud_detail", "fog volume"}, {"detail_b", "fog volume"}, {"detail_g", "fog volume"}}));
  const Texture back = read_vdb(out + "/noise_detail.vdb");
  EXPECT_EQ(back.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(back.width, 32);
}

}  // namespace
}  // namespace skybake

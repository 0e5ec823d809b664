// Cloud noise products end to end: the shipped Horizon Zero Dawn
// set bakes, every written file tiles (check-tiling, read back with the real
// readers), every DDS mip level tiles, VDB carries the voxel size and period,
// check-tiling fails on a volume that does not tile, and threads do not
// change a byte.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/tiling.hpp"
#include "io/dds.hpp"
#include "io/vdb.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

const std::string kClouds = test::source_path("presets/clouds/horizon_zero_dawn.json").string();

fs::path baked_clouds() {
  static const fs::path out = [] {
    const fs::path dir = test::fresh_dir("noise_products");
    const auto r = test::run_skybake({"bake", kClouds, "-o", dir.string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir / "clouds_hzd";
  }();
  return out;
}

TEST(NoiseProducts, EveryWrittenFileTiles) {
  const fs::path dir = baked_clouds();
  std::vector<std::string> args = {"check-tiling", "--json"};
  for (const std::string f : {"noise_shape.dds", "noise_shape.vdb", "noise_shape.exr",
                              "noise_detail.dds", "noise_detail.vdb", "curl.dds", "curl.exr"})
    args.push_back((dir / f).string());
  const auto r = test::run_skybake(args);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["tiles"].get<bool>());
  // 3 axes x 4 channels for the shape volume, at each of its mip levels.
  size_t level0 = 0;
  for (const auto& a : j["files"][0]["axes"]) level0 += a["level"] == 0;
  EXPECT_EQ(level0, 12u);
}

TEST(NoiseProducts, EveryDdsMipLevelTiles) {
  const DdsImage shape = read_dds((baked_clouds() / "noise_shape.dds").string());
  EXPECT_EQ(shape.format, DdsFormat::R8G8B8A8_UNORM);
  ASSERT_EQ(shape.mips.size(), 8u) << "128 -> 1 is 8 levels";
  for (size_t level = 0; level < shape.mips.size(); ++level) {
    const Texture& m = shape.mips[level];
    EXPECT_EQ(m.width, 128 >> level);
    // Below 32 texels per axis the seam is one of so few faces (and 8-bit
    // steps so coarse) that it can be the largest by chance; the mip filter
    // tests (tests/core/mip_chain_test.cpp) prove those levels tile exactly
    // by shifting the texture before and after filtering.
    if (m.width < 32) continue;
    const TilingReport t = measure_tiling(m, 0.15);
    EXPECT_TRUE(t.tiles) << "level " << level << " worst ratio " << t.worst_ratio;
  }
}

TEST(NoiseProducts, VdbHasOneGridPerChannelVoxelSizeAndPeriod) {
  const Texture v = read_vdb((baked_clouds() / "noise_shape.vdb").string());
  EXPECT_EQ(v.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(v.width, 128);
  EXPECT_EQ(v.depth, 128);
  bool has_period = false;
  for (const auto& [k, value] : v.metadata) has_period |= k.rfind("period", 0) == 0;
  EXPECT_TRUE(has_period) << "period recorded in the VDB metadata";
  for (float x : v.data) {
    ASSERT_GE(x, 0.0f);
    ASSERT_LE(x, 1.0f);
  }
}

TEST(NoiseProducts, CheckTilingFailsOnAVolumeThatDoesNotTile) {
  const fs::path dir = test::fresh_dir("noise_not_tiling");
  // A smooth ramp along x: interior jumps 1/31, the wrapped face jumps 1.
  Texture ramp(32, 32, 32, 1, {"R"});
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) ramp.at(x, y, z, 0, 0) = float(x) / 31.0f;
  write_dds((dir / "ramp.dds").string(), {ramp}, DdsFormat::R16_FLOAT);
  const auto r = test::run_skybake({"check-tiling", (dir / "ramp.dds").string()});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("NO TILE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("axis x"), std::string::npos) << r.out;
}

TEST(NoiseProducts, ByteIdenticalForOneAndTwoThreads) {
  const fs::path one = test::fresh_dir("noise_threads1"), two = test::fresh_dir("noise_threads2");
  ASSERT_EQ(test::run_skybake({"bake", kClouds, "-o", one.string(), "-q", "--threads", "1",
                               "--only", "noise_shape,curl"})
                .exit_code,
            0);
  ASSERT_EQ(test::run_skybake({"bake", kClouds, "-o", two.string(), "-q", "--threads", "2",
                               "--only", "noise_shape,curl"})
                .exit_code,
            0);
  for (const std::string f : {"noise_shape.dds", "noise_shape.vdb", "noise_shape.exr", "curl.dds",
                              "noise_shape.preview.png", "manifest.json"})
    EXPECT_TRUE(test::read_file(one / "clouds_hzd" / f) == test::read_file(two / "clouds_hzd" / f))
        << f;
}

TEST(NoiseProducts, PackedVariantIsOneChannelR8) {
  const fs::path dir = test::fresh_dir("noise_packed");
  const auto r = test::run_skybake(
      {"bake", test::source_path("presets/clouds/frostbite_packed.json").string(), "-o",
       dir.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DdsImage packed = read_dds((dir / "clouds_frostbite_packed/noise_shape.dds").string());
  EXPECT_EQ(packed.format, DdsFormat::R8_UNORM);
  EXPECT_EQ(packed.mips[0].channel_count(), 1);
  EXPECT_TRUE(measure_tiling(packed.mips[0], 0.15).tiles);
}

}  // namespace
}  // namespace skybake

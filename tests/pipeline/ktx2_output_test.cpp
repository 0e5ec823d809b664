// KTX2 through the pipeline: the output writer picks the format the output
// asks for (ktx2_format, else precision and the product's 8-bit default),
// writes the mip chain the output asks for, records the encoding, and the
// file reads back through read_texture_file (what `skybake info` and
// check-tiling use) and read_lossless_output; the loader's rules on
// ktx2_format.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/mip_chain.hpp"
#include "io/output_readback.hpp"
#include "io/texture_file.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

using ::testing::HasSubstr;

Texture volume(int channels) {
  static const std::vector<std::string> names = {"R", "G", "B", "A"};
  Texture tex(8, 4, 4, 1, {names.begin(), names.begin() + channels});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(i % 251) / 256.0f + 0.125f;
  return tex;
}

OutputSpec spec_of(const std::string& product, const std::string& name) {
  OutputSpec spec;
  spec.product = product;
  spec.name = name;
  spec.size = {8, 4, 4};
  spec.formats = {"ktx2"};
  spec.options = nlohmann::json::object({{"product", product}});
  return spec;
}

TEST(Ktx2Output, FloatTableIsWrittenLosslesslyUnderItsName) {
  const fs::path dir = test::fresh_dir("ktx2_output_float");
  const Texture tex = volume(4);
  const OutputSpec spec = spec_of("aerial_perspective", "ap");
  EXPECT_EQ(output_files(spec), std::vector<std::string>{"ap.ktx2"});
  const std::vector<ManifestFile> files =
      write_outputs(tex, *find_product("aerial_perspective"), spec, dir);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].format, "ktx2");
  EXPECT_EQ(files[0].encoding, "R32G32B32A32_SFLOAT");
  const LoadedTexture back = read_texture_file((dir / "ap.ktx2").string());
  EXPECT_EQ(back.format, "ktx2");
  EXPECT_EQ(back.encoding, "R32G32B32A32_SFLOAT");
  EXPECT_EQ(back.mip_levels, 1);
  EXPECT_EQ(back.texture.data, tex.data);

  ManifestEntry entry;
  entry.channels = tex.channels;
  entry.files = files;
  const std::optional<Texture> lossless = read_lossless_output(entry, dir);
  ASSERT_TRUE(lossless.has_value());
  EXPECT_EQ(lossless->data, tex.data);
  EXPECT_EQ(lossless->channels, tex.channels);
}

TEST(Ktx2Output, HalfPrecisionAndAnExplicitFormat) {
  const fs::path dir = test::fresh_dir("ktx2_output_half");
  const Texture tex = volume(4);
  OutputSpec spec = spec_of("aerial_perspective", "half");
  spec.precision = "half";
  EXPECT_EQ(write_outputs(tex, *find_product("aerial_perspective"), spec, dir)[0].encoding,
            "R16G16B16A16_SFLOAT");
  const Texture back = read_texture_file((dir / "half.ktx2").string()).texture;
  ASSERT_EQ(back.data.size(), tex.data.size());
  for (size_t i = 0; i < tex.data.size(); ++i)
    ASSERT_LE(std::abs(back.data[i] - tex.data[i]), std::ldexp(std::abs(tex.data[i]), -11)) << i;

  OutputSpec unorm = spec_of("aerial_perspective", "unorm");
  unorm.options["ktx2_format"] = "R8G8B8A8_UNORM";
  EXPECT_EQ(write_outputs(tex, *find_product("aerial_perspective"), unorm, dir)[0].encoding,
            "R8G8B8A8_UNORM");
}

TEST(Ktx2Output, BlockCompressedFormatsAreWrittenWhenAsked) {
  const fs::path dir = test::fresh_dir("ktx2_output_bc");
  const ProductInfo& detail = *find_product("noise_detail");
  Texture tex(8, 4, 4, 1, {"R", "G", "B"});  // smooth ramps, as noise is inside a block
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c) tex.at(x, y, z, 0, c) = 0.1f + 0.05f * float(x + y + z + c);
  OutputSpec spec = spec_of("noise_detail", "bc1");
  spec.options["ktx2_format"] = "BC1_RGB_UNORM_BLOCK";
  const std::vector<ManifestFile> files = write_outputs(tex, detail, spec, dir);
  EXPECT_EQ(files[0].encoding, "BC1_RGB_UNORM_BLOCK");
  const LoadedTexture back = read_texture_file((dir / "bc1.ktx2").string());
  EXPECT_EQ(back.encoding, "BC1_RGB_UNORM_BLOCK");
  EXPECT_EQ(back.texture.channels, tex.channels);
  EXPECT_EQ(back.mip_levels, mip_count(8, 4, 4));
  // BC1 keeps two 5-6-5 endpoints per 4x4 block and thirds between them
  // (tests/io/ktx2_test.cpp checks the blocks exactly).
  for (size_t i = 0; i < tex.data.size(); ++i)
    ASSERT_NEAR(back.texture.data[i], tex.data[i], 0.06) << i;
}

TEST(Ktx2Output, NoiseVolumesAre8BitWithTheirTileableMipChain) {
  const fs::path dir = test::fresh_dir("ktx2_output_noise");
  const ProductInfo& detail = *find_product("noise_detail");
  for (int channels : {1, 3}) {
    const Texture tex = volume(channels);
    const OutputSpec spec = spec_of("noise_detail", "detail" + std::to_string(channels));
    const std::vector<ManifestFile> files = write_outputs(tex, detail, spec, dir);
    EXPECT_EQ(files[0].encoding, channels == 1 ? "R8_UNORM" : "R8G8B8A8_UNORM");
    const LoadedTexture back = read_texture_file((dir / files[0].path).string());
    EXPECT_EQ(back.texture.channels, tex.channels);
    EXPECT_EQ(back.mip_levels, mip_count(8, 4, 4));  // noise products default to mips
    const std::vector<Texture> chain = build_mip_chain(tex, MipEdge::wrap);
    ASSERT_EQ(back.lower_levels.size(), chain.size() - 1);
    for (size_t p = 1; p < chain.size(); ++p)
      for (size_t i = 0; i < chain[p].data.size(); ++i)
        ASSERT_EQ(back.lower_levels[p - 1].data[i],
                  std::round(std::clamp(chain[p].data[i], 0.0f, 1.0f) * 255.0f) / 255.0f)
            << "level " << p << " value " << i;
  }
}

TEST(Ktx2Output, BakedFilesAreTheSameBytesForOneAndTwoThreads) {
  const fs::path dir = test::fresh_dir("ktx2_output_threads");
  std::ofstream(dir / "scene.json") << R"({"name": "n", "outputs": [
      {"product": "noise_detail", "size": [32, 32, 32], "formats": ["ktx2"]},
      {"product": "noise_shape", "size": [32, 32, 32], "formats": ["ktx2"],
       "pack": "single_channel", "ktx2_format": "BC4_UNORM_BLOCK",
       "perlin": {"period": 4, "octaves": 2}, "perlin_worley": {"period": 4, "octaves": 2},
       "worley": [{"period": 4, "octaves": 2}, {"period": 8, "octaves": 2},
                  {"period": 8, "octaves": 2}]}]})";
  for (const char* threads : {"1", "2"}) {
    const auto r = test::run_skybake(
        {"bake", "scene.json", "-o", std::string("out") + threads, "--threads", threads, "--quiet"},
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const char* file : {"noise_detail.ktx2", "noise_shape.ktx2"}) {
    const std::string one = test::read_file(dir / "out1" / "n" / file);
    EXPECT_GT(one.size(), 32u * 32 * 32 / 2) << file;
    EXPECT_EQ(one, test::read_file(dir / "out2" / "n" / file)) << file;
  }
  EXPECT_EQ(read_texture_file((dir / "out1" / "n" / "noise_shape.ktx2").string()).encoding,
            "BC4_UNORM_BLOCK");
}

}  // namespace
}  // namespace skybake

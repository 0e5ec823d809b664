// EXR files whose skybake:* attributes or header sizes lie: each must be
// refused with an IoError naming the file and the rule, before the texture
// (or any pixel buffer) is allocated.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/exr.hpp"
#include "support/memory_cap.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A `width` x `height` float EXR with channels R (G, B, A), carrying the given
// skybake:* string and int attributes.
std::string write_exr_with(const std::string& name, int width, int height,
                           const std::vector<std::pair<std::string, std::string>>& strings,
                           const std::vector<std::pair<std::string, int>>& ints = {},
                           int tile = 0, int channels = 1) {
  const std::string path = test::scratch_file("hostile_exr", name, name + ".exr");
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  const std::vector<std::string> rgba = {"R", "G", "B", "A"};
  spec.channelnames.assign(rgba.begin(), rgba.begin() + channels);
  if (tile > 0) spec.tile_width = spec.tile_height = tile;
  spec.attribute("compression", "zip");
  for (const auto& [k, v] : strings) spec.attribute("skybake:" + k, v);
  for (const auto& [k, v] : ints) spec.attribute("skybake:" + k, v);
  const std::vector<float> pixels(size_t(width) * height * channels, 0.5f);
  auto out = OIIO::ImageOutput::create("openexr");
  EXPECT_TRUE(out && out->open(path, spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  EXPECT_TRUE(out->close());
  return path;
}

// read_exr's IoError message, or "" when it did not throw one.
std::string refusal(const std::string& path) {
  try {
    read_exr(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileExr, NegativeAtlasWidthIsRefused) {
  const std::string path =
      write_exr_with("negative_width", 8, 8, {{"layout", "atlas"}, {"shape", "-5x4x4x1"}},
                     {{"atlas_columns", 2}, {"atlas_rows", 2}});
  const std::string why = refusal(path);
  EXPECT_THAT(why, HasSubstr(path));
  EXPECT_THAT(why, HasSubstr("expected skybake:shape of the form WxHxDxL with sizes from 1"));
  // The executable ends with a file error, not an abort.
  const auto r = test::run_skybake({"info", path});
  EXPECT_EQ(r.exit_code, 4) << r.err;
}

TEST(HostileExr, AtlasAttributesThatDoNotMatchTheImageAreRefused) {
  // columns * slice width overflows 32 bits: compared in 64 bits.
  EXPECT_THAT(refusal(write_exr_with("atlas_overflow", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "4x4x2147483647x1"}},
                                     {{"atlas_columns", 2147483647},
                                      {"atlas_rows", 1},
                                      {"slice_count", 2147483647},
                                      {"slice_width", 4},
                                      {"slice_height", 4}})),
              HasSubstr("expected part 0 of 8589934588x4, got 8x8"));
  EXPECT_THAT(refusal(write_exr_with("atlas_few_cells", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "4x4x100x1"}},
                                     {{"atlas_columns", 2},
                                      {"atlas_rows", 2},
                                      {"slice_count", 100},
                                      {"slice_width", 4},
                                      {"slice_height", 4}})),
              HasSubstr("expected an atlas of 100 cells (skybake:atlas_columns x "
                        "skybake:atlas_rows), got 2x2"));
  // An atlas has no empty cell: more cells than slices is refused too.
  EXPECT_THAT(refusal(write_exr_with("atlas_empty_cells", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "4x4x3x1"}},
                                     {{"atlas_columns", 2},
                                      {"atlas_rows", 2},
                                      {"slice_count", 3},
                                      {"slice_width", 4},
                                      {"slice_height", 4}})),
              HasSubstr("expected an atlas of 3 cells"));
  EXPECT_THAT(refusal(write_exr_with("atlas_no_columns", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "4x4x4x1"}})),
              HasSubstr("expected skybake:slice_count, slice_width, slice_height 4, 4, 4 "
                        "(skybake:shape), got 0, 0, 0"));
  EXPECT_THAT(refusal(write_exr_with("atlas_layers", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "4x4x4x3"}},
                                     {{"atlas_columns", 2}, {"atlas_rows", 2}})),
              HasSubstr("expected 1 layer in an atlas (skybake:shape), got 3"));
  EXPECT_THAT(refusal(write_exr_with("atlas_big_slice", 8, 8,
                                     {{"layout", "atlas"}, {"shape", "100000x100000x1x1"}},
                                     {{"atlas_columns", 1},
                                      {"atlas_rows", 1},
                                      {"slice_count", 1},
                                      {"slice_width", 100000},
                                      {"slice_height", 100000}})),
              HasSubstr("expected part 0 of 100000x100000, got 8x8"));
}

TEST(HostileExr, ShapeAndChannelAttributesAreCheckedAgainstTheParts) {
  EXPECT_THAT(refusal(write_exr_with("shape_layers", 4, 4, {{"shape", "4x4x1x1000000"}})),
              HasSubstr("expected 1000000 parts for a 4x4x1x1000000 texture, got 1"));
  EXPECT_THAT(refusal(write_exr_with("shape_size", 4, 4, {{"shape", "4096x4096x1x1"}})),
              HasSubstr("expected part 0 of 4096x4096, got 4x4"));
  EXPECT_THAT(refusal(write_exr_with("shape_text", 4, 4, {{"shape", "4x4x1x99999999999"}})),
              HasSubstr("expected skybake:shape of the form WxHxDxL"));
  EXPECT_THAT(refusal(write_exr_with("channels_repeated", 4, 4, {{"channels", "R,R,R,R,R"}})),
              HasSubstr("expected skybake:channels to name distinct channels of the file, got 'R'"));
  EXPECT_THAT(refusal(write_exr_with("channels_unknown", 4, 4, {{"channels", "R,Q"}})),
              HasSubstr("got 'Q'"));
}

// A 16x16 tiled RGBA file whose header is edited to claim 20000x20000 in
// 8192x8192 tiles (with room in the offset table for its 9 tiles): OpenEXR
// opens it, and 20000^2 x 4 float32 channels are 6.4 GB.
std::string write_huge_claim() {
  const std::string path = write_exr_with("huge_claim", 16, 16, {}, {}, 16, 4);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const auto find = [&](const std::string& key) {
    const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
    EXPECT_NE(it, b.end()) << key;
    return size_t(it - b.begin()) + key.size() + 4;  // past the attribute's size field
  };
  const auto put_i32 = [&](size_t at, int32_t v) { std::memcpy(&b[at], &v, 4); };
  const size_t tiles = find(std::string("tiles\0tiledesc\0", 15));
  put_i32(tiles, 8192);
  put_i32(tiles + 4, 8192);
  for (const std::string& key :
       {std::string("dataWindow\0box2i\0", 17), std::string("displayWindow\0box2i\0", 20)}) {
    const size_t box = find(key);
    put_i32(box + 8, 19999);
    put_i32(box + 12, 19999);
  }
  // The offset table: its one entry points just past itself.
  for (size_t k = 0; k + 8 <= b.size(); ++k) {
    uint64_t v;
    std::memcpy(&v, &b[k], 8);
    if (v == k + 8) {
      b.insert(b.begin() + long(k) + 8, 8 * 8, '\0');
      break;
    }
  }
  std::ofstream(path, std::ios::binary).write(b.data(), std::streamsize(b.size()));
  return path;
}

// Refused before allocating: the read ends in the refusal with 64 MiB to
// spare, where the pixels would take 6.4 GB.
TEST(HostileExr, HugeHeaderInATinyFileIsRefusedBeforeAllocation) {
  const std::string path = write_huge_claim();
  ASSERT_LT(fs::file_size(path), 1024u);
  EXPECT_EQ(test::run_with_memory_headroom(
                64 << 20, [&] { return refusal(path).find(path) != std::string::npos ? 0 : 1; }),
            0);
  const std::string why = refusal(path);
  EXPECT_THAT(why, HasSubstr(path));
  EXPECT_THAT(why, HasSubstr("header sizes decode to 6400000000 bytes of float32 pixels from a"));
  EXPECT_THAT(why, HasSubstr("the limit is 4096 times the file size"));
  const auto r = test::run_skybake({"info", path});
  EXPECT_EQ(r.exit_code, 4) << r.err;
}

// Found by exr_reader_fuzz: OpenEXR allocated a string attribute's declared
// size (1.8 GB in a 731-byte file, 15 s) before finding the file too short.
TEST(HostileExr, AttributeSizeLargerThanTheFileIsRefusedBeforeOpenExr) {
  const std::string path = write_exr_with("attribute_size", 4, 4, {{"layout", "image"}});
  std::ifstream in(path, std::ios::binary);
  std::vector<char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::string key("skybake:layout\0string\0", 22);
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  ASSERT_NE(it, b.end());
  const int32_t huge = 1811939425;
  std::memcpy(&*(it + long(key.size())), &huge, 4);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
  const std::string expected = path +
                               ": not an EXR skybake can read safely: attribute "
                               "'skybake:layout' of part 0 declares 1811939425 bytes";
  EXPECT_EQ(test::run_with_memory_headroom(
                64 << 20, [&] { return refusal(path).find(expected) != std::string::npos ? 0 : 1; }),
            0)
      << "the declared 1.8 GB must not be allocated";
  EXPECT_THAT(refusal(path), HasSubstr(expected));
}

TEST(HostileExr, GenuineAtlasStillReads) {
  Texture tex(3, 2, 5, 1, {"R", "G"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(i);
  const std::string path = test::scratch_file("hostile_exr", "genuine", "genuine.exr");
  write_exr(path, tex, ExrPrecision::float32);
  const Texture back = read_exr(path);
  EXPECT_EQ(back.shape_string(), "3x2x5");
  EXPECT_EQ(back.data, tex.data);
}

}  // namespace
}  // namespace skybake

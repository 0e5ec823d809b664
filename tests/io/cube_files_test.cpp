// Tests for the cube-map writers and readers (write_dds_cube, write_ktx2_cube,
// read_dds and read_ktx2 on cube maps). Headers are checked at the offsets of
// the published layouts (Microsoft Learn "DDS_HEADER", "DDS_HEADER_DXT10";
// KTX 2.0 "File Structure"), parsed here and not by our readers; the data
// order (each face's levels in DDS, each level's faces in KTX2) by reading
// the bytes of known texels; the readers' checks of the cube flags.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/half.hpp"
#include "io/dds.hpp"
#include "io/ktx2.hpp"
#include "support/file_bytes.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

using ::testing::HasSubstr;
using test::read_bytes;
using test::u32_at;
using test::u64_at;

// Level `level` of a cube chain whose texel values name their level, layer
// and position: value = 1000 level + 100 layer + 10 y + x + channel / 10.
std::vector<Texture> named_cube_chain(int n, int cubes, int levels) {
  std::vector<Texture> mips;
  for (int m = 0; m < levels; ++m) {
    Texture t(n >> m, n >> m, 1, 6 * cubes, {"R", "G", "B"});
    for (int layer = 0; layer < t.layers; ++layer)
      for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x)
          for (int c = 0; c < 3; ++c)
            t.at(x, y, 0, layer, c) = float(1000 * m + 100 * layer + 10 * y + x) + 0.25f * c;
    mips.push_back(std::move(t));
  }
  return mips;
}

MipLevels pointers(const std::vector<Texture>& mips) {
  MipLevels out;
  for (const Texture& m : mips) out.push_back(&m);
  return out;
}

std::string cube_file(const std::string& name) {
  return (test::test_dir("cube_files") / name).string();
}

TEST(DdsCube, HeaderCarriesTheCubeFlagsAndCountsCubes) {
  const std::vector<Texture> mips = named_cube_chain(8, 2, 3);
  const std::string path = cube_file("two_cubes.dds");
  write_dds_cube(path, pointers(mips), DdsFormat::R32G32B32A32_FLOAT);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 112), 0xFE00u);  // caps2: DDSCAPS2_CUBEMAP | all six faces
  EXPECT_NE(u32_at(b, 108) & 0x8u, 0u);  // caps: DDSCAPS_COMPLEX
  EXPECT_EQ(u32_at(b, 28), 3u);          // mipMapCount
  EXPECT_EQ(u32_at(b, 132), 3u);         // resourceDimension TEXTURE2D
  EXPECT_EQ(u32_at(b, 136), 0x4u);       // miscFlag DDS_RESOURCE_MISC_TEXTURECUBE
  EXPECT_EQ(u32_at(b, 140), 2u);         // arraySize: cubes, not faces
  // Data order: face by face, each with its levels (8x8, 4x4, 2x2 of 16 bytes).
  const size_t face_bytes = (64 + 16 + 4) * 16;
  const size_t second_face_level1 = 148 + face_bytes + 64 * 16;
  float v = 0.0f;
  std::memcpy(&v, &b[second_face_level1], 4);
  EXPECT_EQ(v, 1000.0f + 100.0f);  // level 1, layer 1, texel (0, 0)
}

TEST(DdsCube, ReadsBackAsSixLayersPerCube) {
  const std::vector<Texture> mips = named_cube_chain(4, 1, 3);
  const std::string path = cube_file("cube.dds");
  write_dds_cube(path, pointers(mips), DdsFormat::R16G16B16A16_FLOAT);
  const DdsImage image = read_dds(path);
  EXPECT_TRUE(image.cube);
  ASSERT_EQ(image.mips.size(), 3u);
  EXPECT_EQ(image.mips[0].layers, 6);
  for (size_t m = 0; m < 3; ++m) {
    const int x = std::min(1, mips[m].width - 1);
    EXPECT_EQ(image.mips[m].at(x, x, 0, 5, 2),
              float_from_half(half_from_float(mips[m].at(x, x, 0, 5, 2))))
        << "level " << m;
  }
}

TEST(DdsCube, ReaderRefusesACubeWithoutAllFaces) {
  const std::vector<Texture> mips = named_cube_chain(4, 1, 1);
  const std::string path = cube_file("five_faces.dds");
  write_dds_cube(path, pointers(mips), DdsFormat::R32G32B32A32_FLOAT);
  std::vector<uint8_t> b = read_bytes(path);
  test::put_u32_at(b, 112, 0x7E00);  // -Z missing
  test::write_bytes(path, b);
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("all six faces")));
}

TEST(DdsCube, WriterRefusesFacesThatAreNotSquareOrNotSix) {
  Texture wide(8, 4, 1, 6, {"R"});
  EXPECT_THROW(write_dds_cube(cube_file("wide.dds"), {&wide}, DdsFormat::R32G32B32A32_FLOAT),
               IoError);
  Texture five(4, 4, 1, 5, {"R"});
  EXPECT_THROW(write_dds_cube(cube_file("five.dds"), {&five}, DdsFormat::R32G32B32A32_FLOAT),
               IoError);
  EXPECT_FALSE(std::filesystem::exists(cube_file("five.dds")));
}

TEST(Ktx2Cube, HeaderHasSixFacesAndNoLayersForOneCube) {
  const std::vector<Texture> mips = named_cube_chain(8, 1, 4);
  const std::string path = cube_file("cube.ktx2");
  write_ktx2_cube(path, pointers(mips), Ktx2Format::R16G16B16A16_SFLOAT);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 12), 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(u32_at(b, 20), 8u);   // pixelWidth
  EXPECT_EQ(u32_at(b, 28), 0u);   // pixelDepth
  EXPECT_EQ(u32_at(b, 32), 0u);   // layerCount: one cube is not an array
  EXPECT_EQ(u32_at(b, 36), 6u);   // faceCount
  EXPECT_EQ(u32_at(b, 40), 4u);   // levelCount
  // Level 2 (2x2 faces of 8 bytes): its faces in order, face 3's first texel.
  const uint64_t offset = u64_at(b, 80 + 24 * 2), length = u64_at(b, 80 + 24 * 2 + 8);
  EXPECT_EQ(length, 6u * 4u * 8u);
  uint16_t h = 0;
  std::memcpy(&h, &b[offset + 3 * 4 * 8], 2);
  EXPECT_EQ(float_from_half(h), 2000.0f + 300.0f);
}

TEST(Ktx2Cube, CubeArrayCountsCubesAndReadsBack) {
  const std::vector<Texture> mips = named_cube_chain(4, 3, 2);
  const std::string path = cube_file("cubes.ktx2");
  write_ktx2_cube(path, pointers(mips), Ktx2Format::R32G32B32A32_SFLOAT);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 32), 3u);  // layerCount: cubes
  EXPECT_EQ(u32_at(b, 36), 6u);
  const Ktx2Image image = read_ktx2(path);
  EXPECT_TRUE(image.cube);
  ASSERT_EQ(image.mips.size(), 2u);
  EXPECT_EQ(image.mips[1].layers, 18);
  EXPECT_EQ(image.mips[1].at(1, 0, 0, 17, 1), mips[1].at(1, 0, 0, 17, 1));
}

TEST(Ktx2Cube, ReaderRefusesOtherFaceCounts) {
  const std::vector<Texture> mips = named_cube_chain(4, 1, 1);
  const std::string path = cube_file("three_faces.ktx2");
  write_ktx2_cube(path, pointers(mips), Ktx2Format::R32G32B32A32_SFLOAT);
  std::vector<uint8_t> b = read_bytes(path);
  test::put_u32_at(b, 36, 3);
  test::write_bytes(path, b);
  EXPECT_THAT([&] { read_ktx2(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("expected faceCount 1 or 6")));
}

}  // namespace
}  // namespace skybake

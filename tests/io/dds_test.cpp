// Tests for io/dds.hpp. Headers are checked byte by byte at the offsets of
// Microsoft's documented layout ("DDS_HEADER", "DDS_PIXELFORMAT",
// "DDS_HEADER_DXT10"), parsed here and not through our reader; the data order
// against the "Programming Guide for DDS"; round trips for every format and
// shape within the format's precision; and the refusals (non-finite values,
// bad mip chains, truncated or foreign files); dds_format_name_test.cpp has
// the format names.
#include "io/dds.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/mip_chain.hpp"
#include "io/dds_format_table.hpp"
#include "support/file_bytes.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::read_bytes;
using test::u32_at;

// A fresh scratch folder per test.
std::string scratch_dir() { return test::test_dir("dds").string(); }

// Deterministic values in [lo, hi).
float scrambled(size_t i, uint32_t seed, float lo, float hi) {
  uint32_t h = uint32_t(i) * 2654435761u ^ (seed * 40503u + 0x9E3779B9u);
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  return lo + (hi - lo) * float(h % 100000) / 100000.0f;
}

std::vector<std::string> rgba(int n) {
  const std::vector<std::string> all = {"R", "G", "B", "A"};
  return {all.begin(), all.begin() + n};
}

Texture filled(int w, int h, int d, int layers, int channels, uint32_t seed, float lo, float hi) {
  Texture t(w, h, d, layers, rgba(channels));
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = scrambled(i, seed, lo, hi);
  return t;
}

// A chain of independent levels (values differ per level, so a level written
// in the wrong place shows up).
std::vector<Texture> chain(int w, int h, int d, int layers, int levels, int channels, float lo,
                           float hi) {
  std::vector<Texture> mips;
  for (int i = 0; i < levels; ++i)
    mips.push_back(filled(std::max(1, w >> i), std::max(1, h >> i), std::max(1, d >> i), layers,
                          channels, uint32_t(i + 1), lo, hi));
  return mips;
}

// ---- header layout -----------------------------------------------------------

constexpr uint32_t DDSD_CAPS = 0x1, DDSD_HEIGHT = 0x2, DDSD_WIDTH = 0x4, DDSD_PITCH = 0x8;
constexpr uint32_t DDSD_PIXELFORMAT = 0x1000, DDSD_MIPMAPCOUNT = 0x20000, DDSD_DEPTH = 0x800000;
constexpr uint32_t DDSCAPS_COMPLEX = 0x8, DDSCAPS_TEXTURE = 0x1000, DDSCAPS_MIPMAP = 0x400000;
constexpr uint32_t DDSCAPS2_VOLUME = 0x200000;
constexpr uint32_t DDSD_LINEARSIZE = 0x80000;
// DDS_HEADER_DXT10.miscFlags2: the fourth channel holds data (custom), or the
// format's alpha is left at 1 (opaque).
constexpr uint32_t kAlphaOpaque = 3, kAlphaCustom = 4;
constexpr uint32_t kRequired = DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT | DDSD_PITCH;

struct Expected {
  uint32_t flags, width, height, depth, mips, caps, caps2, dxgi, dimension, array_size;
  uint32_t pitch, data_bytes;
  uint32_t alpha_mode = 0;  // DDS_ALPHA_MODE_UNKNOWN unless the test says otherwise
};

void check_header(const std::vector<uint8_t>& b, const Expected& e) {
  ASSERT_GE(b.size(), 148u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "DDS ");
  EXPECT_EQ(u32_at(b, 4), 124u);  // dwSize
  EXPECT_EQ(u32_at(b, 8), e.flags);
  EXPECT_EQ(u32_at(b, 12), e.height);
  EXPECT_EQ(u32_at(b, 16), e.width);
  EXPECT_EQ(u32_at(b, 20), e.pitch);
  if (e.flags & DDSD_DEPTH) {
    EXPECT_EQ(u32_at(b, 24), e.depth);
  }
  EXPECT_EQ(u32_at(b, 28), e.mips);  // we always record the level count
  for (size_t off = 32; off < 76; off += 4) EXPECT_EQ(u32_at(b, off), 0u) << "reserved " << off;
  EXPECT_EQ(u32_at(b, 76), 32u);   // ddspf.dwSize
  EXPECT_EQ(u32_at(b, 80), 0x4u);  // DDPF_FOURCC
  EXPECT_EQ(std::string(b.begin() + 84, b.begin() + 88), "DX10");
  for (size_t off = 88; off < 108; off += 4) EXPECT_EQ(u32_at(b, off), 0u) << "ddspf " << off;
  EXPECT_EQ(u32_at(b, 108), e.caps);
  EXPECT_EQ(u32_at(b, 112), e.caps2);
  EXPECT_EQ(u32_at(b, 116), 0u);
  EXPECT_EQ(u32_at(b, 120), 0u);
  EXPECT_EQ(u32_at(b, 124), 0u);
  EXPECT_EQ(u32_at(b, 128), e.dxgi);
  EXPECT_EQ(u32_at(b, 132), e.dimension);
  EXPECT_EQ(u32_at(b, 136), 0u);  // miscFlag: not a cube map
  EXPECT_EQ(u32_at(b, 140), e.array_size);
  EXPECT_EQ(u32_at(b, 144), e.alpha_mode);  // miscFlags2
  EXPECT_EQ(b.size(), 148u + e.data_bytes);
}

TEST(DdsHeader, Plain2D) {
  const std::string path = scratch_dir() + "/a.dds";
  write_dds(path, {filled(8, 4, 1, 1, 4, 1, 0, 1)}, DdsFormat::R16G16B16A16_FLOAT);
  // 8 bytes per texel: pitch 64, data 8 * 4 * 8.
  check_header(read_bytes(path),
               {kRequired, 8, 4, 0, 1, DDSCAPS_TEXTURE, 0, 10, 3, 1, 64, 8 * 4 * 8,
                kAlphaCustom});
  EXPECT_EQ(u32_at(read_bytes(path), 8) & (DDSD_MIPMAPCOUNT | DDSD_DEPTH), 0u);
}

TEST(DdsHeader, VolumeWithFullMipChain) {
  const std::string path = scratch_dir() + "/v.dds";
  // 8x4x4 -> 4x2x2 -> 2x1x1 -> 1x1x1, one byte per texel.
  write_dds(path, chain(8, 4, 4, 1, 4, 1, 0, 1), DdsFormat::R8_UNORM);
  check_header(read_bytes(path), {kRequired | DDSD_DEPTH | DDSD_MIPMAPCOUNT, 8, 4, 4, 4,
                                  DDSCAPS_TEXTURE | DDSCAPS_COMPLEX | DDSCAPS_MIPMAP,
                                  DDSCAPS2_VOLUME, 61, 4, 1, 8, 128 + 16 + 2 + 1});
}

TEST(DdsHeader, ArrayWithMips) {
  const std::string path = scratch_dir() + "/arr.dds";
  write_dds(path, chain(4, 4, 1, 3, 2, 3, 0, 1), DdsFormat::R11G11B10_FLOAT);
  check_header(read_bytes(path), {kRequired | DDSD_MIPMAPCOUNT, 4, 4, 0, 2,
                                  DDSCAPS_TEXTURE | DDSCAPS_COMPLEX | DDSCAPS_MIPMAP, 0, 26, 3, 3,
                                  16, 3 * (16 + 4) * 4});
}

TEST(DdsHeader, ArrayWithoutMipsIsComplex) {
  const std::string path = scratch_dir() + "/arr.dds";
  write_dds(path, {filled(5, 3, 1, 2, 4, 1, 0, 1)}, DdsFormat::R32G32B32A32_FLOAT);
  check_header(read_bytes(path), {kRequired, 5, 3, 0, 1, DDSCAPS_TEXTURE | DDSCAPS_COMPLEX, 0, 2, 3,
                                  2, 5 * 16, 2 * 5 * 3 * 16, kAlphaCustom});
}

TEST(DdsHeader, ReadHeaderReturnsRawFields) {
  const std::string path = scratch_dir() + "/v.dds";
  write_dds(path, chain(4, 2, 8, 1, 2, 4, 0, 1), DdsFormat::R8G8B8A8_UNORM);
  const std::vector<uint8_t> b = read_bytes(path);
  const DdsHeaderInfo h = read_dds_header(path);
  EXPECT_EQ(h.file_size, b.size());
  EXPECT_EQ(h.size, u32_at(b, 4));
  EXPECT_EQ(h.flags, u32_at(b, 8));
  EXPECT_EQ(h.height, 2u);
  EXPECT_EQ(h.width, 4u);
  EXPECT_EQ(h.pitch_or_linear_size, u32_at(b, 20));
  EXPECT_EQ(h.depth, 8u);
  EXPECT_EQ(h.mip_map_count, 2u);
  EXPECT_EQ(h.pixel_format.size, 32u);
  EXPECT_EQ(h.pixel_format.flags, u32_at(b, 80));
  EXPECT_EQ(four_cc_string(h.pixel_format.four_cc), "DX10");
  EXPECT_EQ(h.caps, u32_at(b, 108));
  EXPECT_EQ(h.caps2, u32_at(b, 112));
  EXPECT_TRUE(h.has_dx10);
  EXPECT_EQ(h.dxgi_format, 28u);
  EXPECT_EQ(h.resource_dimension, 4u);
  EXPECT_EQ(h.array_size, 1u);
  EXPECT_EQ(h.misc_flags2, kAlphaCustom);
}

// ---- data order ----------------------------------------------------------------

TEST(DdsLayout, ArrayStoresEachSliceWithAllItsMips) {
  // R8_UNORM codes: 64 * layer + 16 * level + texel index within the level.
  std::vector<Texture> mips;
  for (int level = 0; level < 3; ++level) {
    Texture t(std::max(1, 4 >> level), std::max(1, 2 >> level), 1, 3, {"R"});
    for (int layer = 0; layer < 3; ++layer)
      for (size_t i = 0; i < size_t(t.width * t.height); ++i)
        t.data[layer * t.width * t.height + i] = float(64 * layer + 16 * level + int(i)) / 255.0f;
    mips.push_back(t);
  }
  const std::string path = scratch_dir() + "/order.dds";
  write_dds(path, mips, DdsFormat::R8_UNORM);
  std::vector<uint8_t> expected;
  for (int layer = 0; layer < 3; ++layer)  // Programming Guide: slice, then its mips
    for (int level = 0; level < 3; ++level)
      for (int i = 0; i < (4 >> level) * std::max(1, 2 >> level); ++i)
        expected.push_back(uint8_t(64 * layer + 16 * level + i));
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(std::vector<uint8_t>(b.begin() + 148, b.end()), expected);
}

TEST(DdsLayout, VolumeStoresEachMipWithAllItsSlices) {
  // 4x2x4 -> 2x1x2 -> 1x1x1; codes 32 * level + texel index (x fastest, then y, z).
  std::vector<Texture> mips;
  for (int level = 0; level < 3; ++level) {
    Texture t(std::max(1, 4 >> level), std::max(1, 2 >> level), std::max(1, 4 >> level), 1, {"R"});
    for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(32 * level + int(i)) / 255.0f;
    mips.push_back(t);
  }
  const std::string path = scratch_dir() + "/order.dds";
  write_dds(path, mips, DdsFormat::R8_UNORM);
  std::vector<uint8_t> expected;
  for (int level = 0; level < 3; ++level)  // Programming Guide: mip, then its slices
    for (int z = 0; z < std::max(1, 4 >> level); ++z)
      for (int y = 0; y < std::max(1, 2 >> level); ++y)
        for (int x = 0; x < std::max(1, 4 >> level); ++x)
          expected.push_back(uint8_t(
              32 * level + (z * std::max(1, 2 >> level) + y) * std::max(1, 4 >> level) + x));
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(std::vector<uint8_t>(b.begin() + 148, b.end()), expected);
}

TEST(DdsLayout, LittleEndianFloatsAndHalves) {
  Texture t(1, 1, 1, 1, {"R", "G", "B", "A"});
  t.data = {1.0f, -2.0f, 0.5f, 65504.0f};
  const std::string dir = scratch_dir();
  write_dds(dir + "/f.dds", {t}, DdsFormat::R32G32B32A32_FLOAT);
  write_dds(dir + "/h.dds", {t}, DdsFormat::R16G16B16A16_FLOAT);
  const auto f = read_bytes(dir + "/f.dds"), h = read_bytes(dir + "/h.dds");
  EXPECT_EQ(u32_at(f, 148), 0x3F800000u);  // binary32 1.0
  EXPECT_EQ(u32_at(f, 152), 0xC0000000u);  // binary32 -2.0
  EXPECT_EQ(u32_at(h, 148), 0xC0003C00u);  // halves 1.0 (0x3C00), -2.0 (0xC000)
  EXPECT_EQ(u32_at(h, 152), 0x7BFF3800u);  // halves 0.5 (0x3800), 65504 (0x7BFF)
}

// ---- round trips -----------------------------------------------------------------

// Largest allowed |read - written| for value v in component c: half an ulp
// of the format (float32 exact), including the subnormal spacing near 0.
float tolerance(DdsFormat format, int c, float v) {
  const float a = std::abs(v);
  switch (format) {
    case DdsFormat::R32G32B32A32_FLOAT:
      return 0.0f;
    case DdsFormat::R16G16B16A16_FLOAT:
    case DdsFormat::R16_FLOAT:
      return std::max(a * std::ldexp(1.0f, -11), std::ldexp(1.0f, -25));
    case DdsFormat::R11G11B10_FLOAT:
      return c < 2 ? std::max(a * std::ldexp(1.0f, -7), std::ldexp(1.0f, -21))
                   : std::max(a * std::ldexp(1.0f, -6), std::ldexp(1.0f, -20));
    case DdsFormat::R8G8B8A8_UNORM:
    case DdsFormat::R8G8_UNORM:
    case DdsFormat::R8_UNORM:
      return 0.5f / 255.0f + 1e-6f;
    default:  // block formats: their own tests below and in block_compression_test
      return 0.0f;
  }
}

enum class Shape { plain, array, volume };

class DdsRoundTrip : public ::testing::TestWithParam<std::tuple<DdsFormat, Shape, bool>> {};

TEST_P(DdsRoundTrip, ValuesWithinFormatPrecision) {
  const auto [format, shape, with_mips] = GetParam();
  const int nc = dds_component_count(format);
  const bool unorm = format == DdsFormat::R8G8B8A8_UNORM || format == DdsFormat::R8G8_UNORM ||
                     format == DdsFormat::R8_UNORM;
  const float lo = unorm || format == DdsFormat::R11G11B10_FLOAT ? 0.0f : -50.0f;
  const float hi = unorm ? 1.0f : 50.0f;
  const int w = 8, h = shape == Shape::volume ? 4 : 6, d = shape == Shape::volume ? 2 : 1;
  const int layers = shape == Shape::array ? 3 : 1;
  const int levels = with_mips ? 4 : 1;  // 8 -> 4 -> 2 -> 1: a full chain
  const std::vector<Texture> mips = chain(w, h, d, layers, levels, nc, lo, hi);
  const std::string path = scratch_dir() + "/rt.dds";
  write_dds(path, mips, format);
  const DdsImage image = read_dds(path);
  EXPECT_EQ(image.format, format);
  ASSERT_EQ(image.mips.size(), mips.size());
  for (size_t level = 0; level < mips.size(); ++level) {
    const Texture& in = mips[level];
    const Texture& out = image.mips[level];
    ASSERT_EQ(out.width, in.width);
    ASSERT_EQ(out.height, in.height);
    ASSERT_EQ(out.depth, in.depth);
    ASSERT_EQ(out.layers, in.layers);
    ASSERT_EQ(out.channels, rgba(nc));
    for (size_t i = 0; i < in.data.size(); ++i) {
      const float v = in.data[i];
      ASSERT_LE(std::abs(out.data[i] - v), tolerance(format, int(i % nc), v))
          << "level " << level << " value " << i << " wrote " << v << " read " << out.data[i];
    }
  }
}

std::string round_trip_name(
    const ::testing::TestParamInfo<std::tuple<DdsFormat, Shape, bool>>& info) {
  static const char* const kShapes[] = {"2D", "Array", "Volume"};
  return std::string(dxgi_format_name(std::get<0>(info.param))) + "_" +
         kShapes[int(std::get<1>(info.param))] + (std::get<2>(info.param) ? "_Mips" : "");
}

std::vector<DdsFormat> texel_formats() {
  std::vector<DdsFormat> out;
  for (DdsFormat f : dds_formats())
    if (!dds_is_block_compressed(f)) out.push_back(f);
  return out;
}

INSTANTIATE_TEST_SUITE_P(AllFormatsAndShapes, DdsRoundTrip,
                         ::testing::Combine(::testing::ValuesIn(texel_formats()),
                                            ::testing::Values(Shape::plain, Shape::array,
                                                              Shape::volume),
                                            ::testing::Bool()),
                         round_trip_name);

TEST(DdsConvert, MissingComponentsAreZeroAndMissingAlphaIsOne) {
  const std::string dir = scratch_dir();
  Texture two(2, 1, 1, 1, {"a", "b"});
  two.data = {0.25f, 0.5f, 0.75f, 1.0f};
  write_dds(dir + "/h.dds", {two}, DdsFormat::R16G16B16A16_FLOAT);
  const Texture h = read_dds(dir + "/h.dds").mips[0];
  EXPECT_EQ(h.data, (TexelVector{0.25f, 0.5f, 0, 1, 0.75f, 1.0f, 0, 1}));
  write_dds(dir + "/u.dds", {two}, DdsFormat::R8G8B8A8_UNORM);
  const auto u = read_bytes(dir + "/u.dds");
  EXPECT_EQ(std::vector<uint8_t>(u.begin() + 148, u.end()),
            (std::vector<uint8_t>{64, 128, 0, 255, 191, 255, 0, 255}));  // round(v * 255)
  Texture one(1, 1, 1, 1, {"x"});
  one.data = {2.0f};
  write_dds(dir + "/p.dds", {one}, DdsFormat::R11G11B10_FLOAT);
  EXPECT_EQ(u32_at(read_bytes(dir + "/p.dds"), 148), 16u << 6);  // R = 2.0, G = B = 0
}

TEST(DdsConvert, Unorm8RoundsHalvesAwayFromZeroLikeLround) {
  // Around every half step k + 0.5 of v * 255, a few floats either side.
  std::vector<float> values;
  for (int k = 0; k < 255; ++k) {
    float v = float((k + 0.5) / 255.0);
    for (int i = 0; i < 4; ++i) v = std::nextafter(v, 0.0f);
    for (int i = 0; i < 9; ++i, v = std::nextafter(v, 1.0f)) values.push_back(v);
  }
  for (float v : values) {
    uint8_t byte = 0;
    encode_dds_texel(DdsFormat::R8_UNORM, &v, 1, &byte);
    ASSERT_EQ(long(byte), std::lround(v * 255.0f)) << v;
  }
}

TEST(DdsConvert, Unorm8RowsRoundLikeLroundOfTheClampedProduct) {
  // The row loop (16 values at a time, then one by one) around every half
  // step, out of range, at both zeros and an odd count for the remainder.
  std::vector<float> values{-0.0f, 0.0f, 1.0f, -1e-30f, -3.0f, 1.0000001f, 7.0f, 1e-45f};
  for (int k = 0; k < 255; ++k) {
    float v = float((k + 0.5) / 255.0);
    for (int i = 0; i < 4; ++i) v = std::nextafter(v, 0.0f);
    for (int i = 0; i < 9; ++i, v = std::nextafter(v, 1.0f)) values.push_back(v);
  }
  values.push_back(0.5f);
  std::vector<uint8_t> bytes(values.size());
  encode_dds_texels(DdsFormat::R8_UNORM, values.data(), 1, values.size(), bytes.data());
  for (size_t i = 0; i < values.size(); ++i)
    ASSERT_EQ(long(bytes[i]), std::lround(std::clamp(values[i], 0.0f, 1.0f) * 255.0f))
        << values[i];
}

TEST(DdsConvert, ARowOfTexelsIsEachTexelEncoded) {
  std::vector<float> values(7 * 4);
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) / 9.0f - 0.6f;  // some clamp
  for (DdsFormat format : {DdsFormat::R8G8B8A8_UNORM, DdsFormat::R8G8_UNORM, DdsFormat::R8_UNORM,
                           DdsFormat::R16G16B16A16_FLOAT, DdsFormat::R32G32B32A32_FLOAT})
    for (int nc = 1; nc <= dds_format_info(format).components; ++nc) {
      const size_t bytes = size_t(dds_format_info(format).bytes);
      std::vector<uint8_t> row(7 * bytes), each(7 * bytes);
      encode_dds_texels(format, values.data(), nc, 7, row.data());
      for (size_t t = 0; t < 7; ++t)
        encode_dds_texel(format, values.data() + t * size_t(nc), nc, each.data() + t * bytes);
      EXPECT_EQ(row, each) << dxgi_format_name(format) << " with " << nc << " channels";
    }
}

TEST(DdsLayout, LevelsHeldElsewhereGiveTheSameBytes) {
  const std::string dir = scratch_dir();
  Texture t(16, 8, 4, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i % 97) / 96.0f;
  const std::vector<Texture> chain = build_mip_chain(t, MipEdge::wrap);
  const std::vector<Texture> lower = build_lower_mips(t, MipEdge::wrap);
  MipLevels levels{&t};
  for (const Texture& m : lower) levels.push_back(&m);
  write_dds(dir + "/a.dds", chain, DdsFormat::R8G8B8A8_UNORM);
  write_dds(dir + "/b.dds", levels, DdsFormat::R8G8B8A8_UNORM);
  EXPECT_EQ(read_bytes(dir + "/a.dds"), read_bytes(dir + "/b.dds"));
}

TEST(DdsConvert, OutOfRangeValuesClampToTheFormat) {
  const std::string dir = scratch_dir();
  Texture t(1, 1, 1, 1, {"R", "G", "B", "A"});
  t.data = {1e6f, -1e6f, -0.5f, 1.5f};
  write_dds(dir + "/h.dds", {t}, DdsFormat::R16G16B16A16_FLOAT);
  EXPECT_EQ(read_dds(dir + "/h.dds").mips[0].data,
            (TexelVector{65504.0f, -65504.0f, -0.5f, 1.5f}));
  write_dds(dir + "/u.dds", {t}, DdsFormat::R8G8B8A8_UNORM);
  EXPECT_EQ(read_dds(dir + "/u.dds").mips[0].data, (TexelVector{1, 0, 0, 1}));
  Texture p(1, 1, 1, 1, {"R", "G", "B"});
  p.data = {1e9f, -3.0f, 1e9f};
  write_dds(dir + "/p.dds", {p}, DdsFormat::R11G11B10_FLOAT);
  EXPECT_EQ(read_dds(dir + "/p.dds").mips[0].data, (TexelVector{65024.0f, 0.0f, 64512.0f}));
}

// ---- refusals ----------------------------------------------------------------------

void expect_refused(const std::string& path, const std::vector<Texture>& mips, DdsFormat format,
                    const std::string& message_part) {
  try {
    write_dds(path, mips, format);
    ADD_FAILURE() << "expected IoError containing " << message_part;
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": "));
    EXPECT_THAT(e.what(), HasSubstr(message_part));
  }
  EXPECT_FALSE(fs::exists(path)) << "a refused texture must not create a file";
}

TEST(DdsRefuse, NonFiniteValuesAndNoFileCreated) {
  const std::string path = scratch_dir() + "/bad.dds";
  auto mips = chain(4, 4, 1, 1, 3, 4, 0, 1);
  mips[0].at(1, 2, 0, 0, 3) = std::numeric_limits<float>::infinity();
  expect_refused(path, mips, DdsFormat::R16G16B16A16_FLOAT, "non-finite");
  mips = chain(4, 4, 1, 1, 3, 4, 0, 1);
  mips[2].data[0] = std::nanf("");
  expect_refused(path, mips, DdsFormat::R32G32B32A32_FLOAT, "mip 2: refusing to write");
}

TEST(DdsRefuse, InconsistentMipChains) {
  const std::string path = scratch_dir() + "/bad.dds";
  const auto good = chain(8, 4, 1, 2, 3, 4, 0, 1);
  auto wrong_size = good;
  wrong_size[1] = filled(4, 4, 1, 2, 4, 9, 0, 1);
  expect_refused(path, wrong_size, DdsFormat::R8G8B8A8_UNORM, "mip 1: expected shape 4x2x1");
  auto wrong_layers = good;
  wrong_layers[2] = filled(2, 1, 1, 1, 4, 9, 0, 1);
  expect_refused(path, wrong_layers, DdsFormat::R8G8B8A8_UNORM, "with 2 layers, got 2x1x1");
  auto wrong_channels = good;
  wrong_channels[1].channels[3] = "Z";
  expect_refused(path, wrong_channels, DdsFormat::R8G8B8A8_UNORM, "expected channels [R,G,B,A]");
  auto too_long = chain(2, 2, 1, 1, 2, 1, 0, 1);
  too_long.push_back(filled(1, 1, 1, 1, 1, 9, 0, 1));
  expect_refused(path, too_long, DdsFormat::R8_UNORM, "expected at most 2 mip levels");
  expect_refused(path, {}, DdsFormat::R8_UNORM, "expected at least one mip level");
  expect_refused(path, {filled(2, 2, 1, 1, 4, 1, 0, 1)}, DdsFormat::R16_FLOAT,
                 "expected 1 to 1 channels for R16_FLOAT, got 4");
  expect_refused(path, {filled(2, 2, 2, 2, 1, 1, 0, 1)}, DdsFormat::R8_UNORM, "volume arrays");
}

TEST(DdsRefuse, TruncatedOrPaddedFiles) {
  const std::string dir = scratch_dir();
  const std::string path = dir + "/t.dds";
  write_dds(path, chain(4, 4, 4, 1, 3, 4, 0, 1), DdsFormat::R16G16B16A16_FLOAT);
  const auto size = fs::file_size(path);
  ASSERT_NO_THROW(read_dds(path));
  fs::resize_file(path, size - 1);
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("truncated file")));
  fs::resize_file(path, 140);  // inside the DX10 header
  EXPECT_THROW(read_dds(path), IoError);
  fs::resize_file(path, 20);  // inside DDS_HEADER
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("expected at least 128 bytes")));
  fs::resize_file(path, 0);
  EXPECT_THROW(read_dds(path), IoError);
  write_dds(path, chain(4, 4, 4, 1, 3, 4, 0, 1), DdsFormat::R16G16B16A16_FLOAT);
  fs::resize_file(path, size + 3);
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("trailing bytes")));
  EXPECT_THROW(read_dds(dir + "/missing.dds"), IoError);
}

TEST(DdsRefuse, ForeignHeadersAndFormats) {
  const std::string dir = scratch_dir();
  // A legacy B8G8R8A8 header (D3DFMT_A8R8G8B8: R in the third byte), built by
  // hand from the documented layout: not one of our formats.
  std::vector<uint8_t> b(128 + 4 * 4 * 4, 0);
  auto put = [&](size_t offset, uint32_t v) { test::put_u32_at(b, offset, v); };
  std::copy_n("DDS ", 4, b.begin());
  put(4, 124), put(8, kRequired), put(12, 4), put(16, 4), put(76, 32), put(80, 0x41);
  put(88, 32), put(92, 0xff0000), put(96, 0xff00), put(100, 0xff), put(104, 0xff000000);
  test::write_bytes(dir + "/bgra.dds", b);
  EXPECT_THAT([&] { read_dds(dir + "/bgra.dds"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr(
                  "expected a DX10 header or the legacy pixel format of one of "
                  "R32G32B32A32_FLOAT, R16G16B16A16_FLOAT, R8G8B8A8_UNORM, R8G8_UNORM, R16_FLOAT, "
                  "R8_UNORM, BC1_UNORM, BC3_UNORM, BC4_UNORM, BC5_UNORM, got flags 0x41, 32 bits, "
                  "masks 0xff0000 0xff00 0xff 0xff000000")));
  put(80, 0x4);
  std::copy_n("DXT3", 4, b.begin() + 84);
  test::write_bytes(dir + "/dxt3.dds", b);
  EXPECT_THAT([&] { read_dds(dir + "/dxt3.dds"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("got FourCC \"DXT3\"")));
  // Not a DDS file at all.
  std::ofstream(dir + "/png.dds", std::ios::binary) << std::string(200, 'x');
  EXPECT_THAT([&] { read_dds(dir + "/png.dds"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("expected the magic \"DDS \"")));
  // A DX10 file with a format we do not read (BC7_UNORM = 98).
  const std::string path = dir + "/bc7.dds";
  write_dds(path, {filled(4, 4, 1, 1, 1, 1, 0, 1)}, DdsFormat::R8_UNORM);
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(128);
  const char bc7[4] = {98, 0, 0, 0};
  f.write(bc7, 4);
  f.close();
  EXPECT_THAT([&] { read_dds(path); }, ::testing::ThrowsMessage<IoError>(HasSubstr("got 98")));
}

// ---- an independent reader ------------------------------------------------------

std::string nvddsinfo(const std::string& path) {
  FILE* pipe = popen(("nvddsinfo '" + path + "' 2>&1").c_str(), "r");
  if (!pipe) return "";
  std::string out;
  char buf[256];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  pclose(pipe);
  return out;
}

TEST(DdsExternal, NvddsinfoReadsOurHeaders) {
  // NVIDIA Texture Tools' header dump: a second, independent DDS reader.
  if (std::system("command -v nvddsinfo > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "nvddsinfo (libnvtt-bin) not installed";
  const std::string dir = scratch_dir();
  write_dds(dir + "/2d.dds", chain(16, 8, 1, 1, 5, 4, 0, 1), DdsFormat::R8G8B8A8_UNORM);
  const std::string plain = nvddsinfo(dir + "/2d.dds");
  for (const char* line :
       {"Width: 16", "Height: 8", "Pitch: 64", "Mipmap count: 5", "FourCC: 'DX10'",
        "DXGI Format: 28 (R8G8B8A8_UNORM)", "Resource dimension: 3 (TEXTURE2D)", "Array size: 1"})
    EXPECT_THAT(plain, HasSubstr(line));
  write_dds(dir + "/3d.dds", chain(4, 8, 16, 1, 2, 4, 0, 1), DdsFormat::R16G16B16A16_FLOAT);
  const std::string volume = nvddsinfo(dir + "/3d.dds");
  for (const char* line :
       {"Depth: 16", "DDSD_DEPTH", "Caps 2: 0x00200000", "DXGI Format: 10 (R16G16B16A16_FLOAT)",
        "Resource dimension: 4 (TEXTURE3D)"})
    EXPECT_THAT(volume, HasSubstr(line));
  write_dds(dir + "/arr.dds", {filled(4, 4, 1, 3, 3, 1, 0, 1)}, DdsFormat::R11G11B10_FLOAT);
  const std::string array = nvddsinfo(dir + "/arr.dds");
  for (const char* line : {"DXGI Format: 26 (R11G11B10_FLOAT)", "Array size: 3"})
    EXPECT_THAT(array, HasSubstr(line));
  // A block-compressed volume: linear size of one top slice (2 x 2 blocks).
  write_dds(dir + "/bc3.dds", chain(8, 8, 4, 1, 4, 4, 0, 1), DdsFormat::BC3_UNORM);
  const std::string bc3 = nvddsinfo(dir + "/bc3.dds");
  for (const char* line : {"DDSD_LINEARSIZE", "Linear size: 64", "Depth: 4", "Mipmap count: 4",
                           "DXGI Format: 77 (BC3_UNORM)", "Resource dimension: 4 (TEXTURE3D)"})
    EXPECT_THAT(bc3, HasSubstr(line));
  // Legacy headers: a FourCC, luminance (DDPF_LUMINANCE 0x20000, which
  // nvddsinfo prints as a number) and RGBA masks, and no DX10 header.
  write_dds(dir + "/ati2.dds", chain(8, 4, 1, 1, 4, 2, 0, 1), DdsFormat::BC5_UNORM,
            DdsHeader::legacy);
  const std::string ati2 = nvddsinfo(dir + "/ati2.dds");
  for (const char* line : {"FourCC: 'ATI2'", "Linear size: 32", "Mipmap count: 4"})
    EXPECT_THAT(ati2, HasSubstr(line));
  EXPECT_THAT(ati2, ::testing::Not(HasSubstr("DX10 Header")));
  write_dds(dir + "/l8.dds", {filled(4, 4, 1, 1, 1, 1, 0, 1)}, DdsFormat::R8_UNORM,
            DdsHeader::legacy);
  for (const char* line : {"Flags: 0x00020000", "Bit count: 8", "Red mask: 0x000000FF"})
    EXPECT_THAT(nvddsinfo(dir + "/l8.dds"), HasSubstr(line));
  write_dds(dir + "/rgba.dds", {filled(4, 4, 1, 1, 4, 1, 0, 1)}, DdsFormat::R8G8B8A8_UNORM,
            DdsHeader::legacy);
  for (const char* line : {"DDPF_RGB", "DDPF_ALPHAPIXELS", "Bit count: 32", "Red mask: 0x000000FF",
                           "Alpha mask: 0xFF000000", "Pitch: 16"})
    EXPECT_THAT(nvddsinfo(dir + "/rgba.dds"), HasSubstr(line));
}

}  // namespace
}  // namespace skybake

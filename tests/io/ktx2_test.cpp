// Tests for io/ktx2: exact round trips through our strict reader for every
// shape and format, the layout the specification asks for (read with plain
// byte offsets, not with our reader), and refusals of truncated, padded and
// forged files with their messages. tests/io/ktx2_external_test.cpp reads the
// files with an independent reader.
#include "io/ktx2.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/half.hpp"
#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "support/file_bytes.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string tmp(const std::string& test, const std::string& file) {
  return test::scratch_file("io_ktx2", test, file);
}

using test::put_u32_at;
using test::read_bytes;
using test::u32_at;
using test::u64_at;
using test::write_bytes;

// Values each format stores exactly: k/255 for unorm8, halves of small
// integers for half, anything finite (here irrational-looking) for float32.
float exact_value(Ktx2Encoding e, size_t i) {
  switch (e) {
    case Ktx2Encoding::unorm8:
      return float(i * 37 % 256) / 255.0f;
    case Ktx2Encoding::half:
      return float_from_half(half_from_float(float(int(i % 97) - 40) / 8.0f));
    case Ktx2Encoding::float32:
      return float(std::sin(0.731 * double(i)) * 1000.0);
    case Ktx2Encoding::bc:  // lossy: any values in [0, 1] (Ktx2BlockRoundTrip)
      return float(0.5 + 0.5 * std::sin(0.731 * double(i)));
  }
  return 0.0f;
}

Texture make(int w, int h, int d, int layers, int channels, Ktx2Encoding e, size_t seed = 0) {
  static const std::vector<std::string> names = {"R", "G", "B", "A"};
  Texture t(w, h, d, layers, {names.begin(), names.begin() + channels});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = exact_value(e, i + seed);
  return t;
}

// A chain whose every level holds its own exact values.
std::vector<Texture> chain(int w, int h, int d, int layers, int channels, Ktx2Encoding e,
                           bool mips) {
  std::vector<Texture> levels;
  const int n = mips ? mip_count(w, h, d) : 1;
  for (int p = 0; p < n; ++p)
    levels.push_back(make(std::max(1, w >> p), std::max(1, h >> p), std::max(1, d >> p), layers,
                          channels, e, size_t(p) * 1000));
  levels[0].metadata["product"] = "noise_shape";
  levels[0].metadata["mu_min"] = -0.20000000000000001;
  return levels;
}

struct Case {
  Ktx2Format format;
  int w, h, d, layers, channels;
  bool mips;
};

std::string case_name(const testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  return fmt::format("{}_{}x{}x{}x{}_{}ch{}", ktx2_format_name(c.format), c.w, c.h, c.d, c.layers,
                     c.channels, c.mips ? "_mips" : "");
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const Ktx2FormatInfo& f : ktx2_formats())
    for (bool mips : {false, true}) {
      if (f.encoding == Ktx2Encoding::bc) continue;                 // lossy: Ktx2BlockRoundTrip
      cases.push_back({f.format, 7, 5, 1, 1, f.components, mips});  // 2D, odd sizes
      cases.push_back({f.format, 8, 4, 1, 3, std::min(f.components, 3), mips});  // 2D array
      cases.push_back({f.format, 4, 6, 5, 1, 1, mips});                          // 3D
    }
  return cases;
}

class Ktx2RoundTrip : public testing::TestWithParam<Case> {};

TEST_P(Ktx2RoundTrip, EveryTexelChannelAndKeyComesBackExactly) {
  const Case& c = GetParam();
  const Ktx2FormatInfo& f = ktx2_format_info(c.format);
  const std::vector<Texture> mips = chain(c.w, c.h, c.d, c.layers, c.channels, f.encoding, c.mips);
  const std::string path =
      tmp("round_trip", case_name(testing::TestParamInfo<Case>(c, 0)) + ".ktx2");
  write_ktx2(path, mips, c.format);
  const Ktx2Image image = read_ktx2(path);
  EXPECT_EQ(image.format, c.format);
  ASSERT_EQ(image.mips.size(), mips.size());
  for (size_t p = 0; p < mips.size(); ++p) {
    const Texture& got = image.mips[p];
    EXPECT_EQ(got.shape_string(), mips[p].shape_string()) << p;
    EXPECT_EQ(got.channels, mips[p].channels) << p;
    EXPECT_EQ(got.data, mips[p].data) << "level " << p;
  }
  EXPECT_EQ(image.mips[0].metadata, mips[0].metadata);
}

INSTANTIATE_TEST_SUITE_P(AllShapesAndFormats, Ktx2RoundTrip, testing::ValuesIn(all_cases()),
                         case_name);

// What the reader must return for a block-compressed level: each slice
// encoded and decoded by io/block_compression, the texture's channels kept.
Texture through_blocks(const Texture& m, BcFormat bc) {
  Texture out = m;
  const size_t nc = size_t(m.channel_count()), decoded = size_t(bc_decoded_channel_count(bc));
  for (int layer = 0; layer < m.layers; ++layer)
    for (int z = 0; z < m.depth; ++z) {
      const std::vector<uint8_t> blocks =
          encode_bc(m.texel(0, 0, z, layer), m.width, m.height, int(nc), bc);
      const std::vector<float> texels = decode_bc(blocks.data(), m.width, m.height, bc);
      float* dst = out.texel(0, 0, z, layer);
      for (size_t t = 0; t < size_t(m.width) * size_t(m.height); ++t)
        for (size_t c = 0; c < nc; ++c) dst[t * nc + c] = texels[t * decoded + c];
    }
  return out;
}

TEST(Ktx2BlockRoundTrip, EveryLevelComesBackAsItsBlocksDecode) {
  for (const Ktx2FormatInfo& f : ktx2_formats()) {
    if (f.encoding != Ktx2Encoding::bc) continue;
    const struct {
      int w, h, d, layers;
    } shapes[] = {{7, 5, 1, 1}, {8, 8, 1, 3}, {4, 6, 5, 1}, {1, 1, 1, 1}};
    for (const auto& sh : shapes)
      for (int channels = 1; channels <= f.components; ++channels) {
        SCOPED_TRACE(fmt::format("{} {}x{}x{}x{} {} channels", f.name, sh.w, sh.h, sh.d, sh.layers,
                                 channels));
        const std::vector<Texture> mips =
            chain(sh.w, sh.h, sh.d, sh.layers, channels, Ktx2Encoding::bc, true);
        const std::string path = tmp("block_round_trip", std::string(f.name) + ".ktx2");
        write_ktx2(path, mips, f.format);
        const Ktx2Image image = read_ktx2(path);
        ASSERT_EQ(image.mips.size(), mips.size());
        for (size_t p = 0; p < mips.size(); ++p) {
          EXPECT_EQ(image.mips[p].channels, mips[p].channels);
          EXPECT_EQ(image.mips[p].data, through_blocks(mips[p], f.bc).data) << "level " << p;
        }
        EXPECT_EQ(image.mips[0].metadata, mips[0].metadata);
      }
  }
}

TEST(Ktx2Layout, BlockLevelsHoldWholeBlocks) {
  // BC1, 6x5 with mips: levels 6x5, 3x2, 1x1 take 2x2, 1x1, 1x1 blocks of 8 bytes.
  const std::string path = tmp("layout", "bc1.ktx2");
  write_ktx2(path, chain(6, 5, 1, 1, 3, Ktx2Encoding::bc, true), Ktx2Format::BC1_RGB_UNORM_BLOCK);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 12), 131u);  // VK_FORMAT_BC1_RGB_UNORM_BLOCK
  EXPECT_EQ(u32_at(b, 16), 1u);    // typeSize of a block format
  const uint64_t lengths[] = {32, 8, 8};
  for (int p = 0; p < 3; ++p) {
    EXPECT_EQ(u64_at(b, 80 + 24 * size_t(p) + 8), lengths[p]) << p;
    EXPECT_EQ(u64_at(b, 80 + 24 * size_t(p)) % 8, 0u) << p;
  }
}

TEST(Ktx2Layout, HeaderIndexAndLevelsSmallestFirstAtAlignedOffsets) {
  // R16_SFLOAT: 2-byte texels, so levels need padding to lcm(2, 4) = 4.
  const std::vector<Texture> mips = chain(5, 3, 1, 1, 1, Ktx2Encoding::half, true);
  const std::string path = tmp("layout", "r16.ktx2");
  write_ktx2(path, mips, Ktx2Format::R16_SFLOAT);
  const std::vector<uint8_t> b = read_bytes(path);
  ASSERT_GE(b.size(), 80u);
  EXPECT_EQ(std::vector<uint8_t>(b.begin(), b.begin() + 12),
            (std::vector<uint8_t>{0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A,
                                  0x0A}));
  const std::vector<uint32_t> header = {76, 2, 5, 3, 0, 0, 1, 3, 0};
  for (size_t i = 0; i < header.size(); ++i) EXPECT_EQ(u32_at(b, 12 + 4 * i), header[i]) << i;
  const uint32_t dfd_offset = u32_at(b, 48), dfd_length = u32_at(b, 52);
  const uint32_t kvd_offset = u32_at(b, 56), kvd_length = u32_at(b, 60);
  EXPECT_EQ(dfd_offset, 80u + 3 * 24);
  EXPECT_EQ(dfd_length, 4u + 24 + 16);  // one sample
  EXPECT_EQ(u32_at(b, dfd_offset), dfd_length);
  EXPECT_EQ(kvd_offset, dfd_offset + dfd_length);
  EXPECT_EQ(kvd_length % 4, 0u);
  EXPECT_EQ(u64_at(b, 64), 0u);
  EXPECT_EQ(u64_at(b, 72), 0u);
  // Level sizes 5x3, 2x1, 1x1 of 2 bytes; level 2 first in the file.
  const uint64_t lengths[] = {30, 4, 2};
  uint64_t expected_offset = (kvd_offset + kvd_length + 3) / 4 * 4;
  for (int p = 2; p >= 0; --p) {
    const size_t e = 80 + 24 * size_t(p);
    EXPECT_EQ(u64_at(b, e), expected_offset) << p;
    EXPECT_EQ(u64_at(b, e + 8), lengths[p]) << p;
    EXPECT_EQ(u64_at(b, e + 16), lengths[p]) << p;
    expected_offset = (expected_offset + lengths[p] + 3) / 4 * 4;
    if (p == 0) {
      EXPECT_EQ(u64_at(b, e) + lengths[0], b.size());
    }
  }
  // Level 0 texel (0, 0) as a little-endian half.
  const uint64_t level0 = u64_at(b, 80);
  EXPECT_EQ(uint16_t(b[level0] | b[level0 + 1] << 8), half_from_float(mips[0].data[0]));
}

TEST(Ktx2Layout, KeyValueDataIsSortedPaddedAndNulTerminated) {
  const std::string path = tmp("kvd", "volume.ktx2");
  write_ktx2(path, chain(4, 4, 4, 1, 1, Ktx2Encoding::float32, false), Ktx2Format::R32_SFLOAT);
  const Ktx2Image image = read_ktx2(path);
  std::vector<std::string> keys;
  for (const auto& [k, v] : image.key_values) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"KTXorientation", "KTXwriter", "skybake.channels",
                                            "skybake.mu_min", "skybake.product"}));
  EXPECT_EQ(image.key_values[0].second, std::string("rdi", 4));
  EXPECT_EQ(image.key_values[1].second, "skybake " SKYBAKE_VERSION + std::string(1, '\0'));
  EXPECT_EQ(image.key_values[2].second, std::string("[\"R\"]", 6));
  EXPECT_EQ(image.key_values[4].second, std::string("\"noise_shape\"", 14));
}

TEST(Ktx2Convert, MissingComponentsAreZeroMissingAlphaOneAndRangesClamp) {
  Texture t(2, 1, 1, 1, {"R", "G", "B"});
  t.data = {2.0f, -1.0f, 0.5f, 1e6f, -1e6f, 0.25f};
  const std::string path = tmp("convert", "clamp.ktx2");
  write_ktx2(path, {t}, Ktx2Format::R8G8B8A8_UNORM);
  Ktx2Image unorm = read_ktx2(path);
  EXPECT_EQ(unorm.mips[0].channels, t.channels);  // the padding alpha is not a channel
  EXPECT_EQ(unorm.mips[0].data,
            (TexelVector{1.0f, 0.0f, 128 / 255.0f, 1.0f, 0.0f, 64 / 255.0f}));
  const std::vector<uint8_t> b = read_bytes(path);
  const uint64_t level0 = u64_at(b, 80);
  EXPECT_EQ(b[level0 + 3], 255);  // alpha of a 3-channel texture
  write_ktx2(path, {t}, Ktx2Format::R16G16B16A16_SFLOAT);
  EXPECT_EQ(read_ktx2(path).mips[0].data,
            (TexelVector{2.0f, -1.0f, 0.5f, 65504.0f, -65504.0f, 0.25f}));
}

TEST(Ktx2Refuse, BadTexturesCreateNoFile) {
  const std::string path = tmp("refuse", "bad.ktx2");
  Texture nan = make(2, 2, 1, 1, 1, Ktx2Encoding::float32);
  nan.data[3] = std::nanf("");
  EXPECT_THROW(write_ktx2(path, {nan}, Ktx2Format::R32_SFLOAT), IoError);
  Texture four = make(2, 2, 1, 1, 4, Ktx2Encoding::float32);
  try {
    write_ktx2(path, {four}, Ktx2Format::R8G8_UNORM);
    ADD_FAILURE() << "no refusal";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("expected 1 to 2 channels for R8G8_UNORM, got 4"));
  }
  Texture volume_array = make(2, 2, 2, 2, 1, Ktx2Encoding::float32);
  EXPECT_THROW(write_ktx2(path, {volume_array}, Ktx2Format::R32_SFLOAT), IoError);
  std::vector<Texture> bad_chain = {make(4, 4, 1, 1, 1, Ktx2Encoding::float32),
                                    make(3, 2, 1, 1, 1, Ktx2Encoding::float32)};
  EXPECT_THROW(write_ktx2(path, bad_chain, Ktx2Format::R32_SFLOAT), IoError);
  Texture reserved = make(2, 2, 1, 1, 1, Ktx2Encoding::float32);
  reserved.metadata["channels"] = "x";
  EXPECT_THROW(write_ktx2(path, {reserved}, Ktx2Format::R32_SFLOAT), Error);
  EXPECT_FALSE(fs::exists(path));
}

// A valid file (2D 8x4, RGBA8, 4 levels: the descriptor at byte 176, 92
// bytes, then the key/value data at 268), then changed by `edit`; the
// message of read_ktx2 on the result.
template <typename Edit>
std::string refusal(const std::string& name, Edit edit) {
  const std::string path = tmp("forged", name + ".ktx2");
  write_ktx2(path, chain(8, 4, 1, 1, 4, Ktx2Encoding::unorm8, true), Ktx2Format::R8G8B8A8_UNORM);
  std::vector<uint8_t> b = read_bytes(path);
  edit(b);
  write_bytes(path, b);
  try {
    read_ktx2(path);
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;  // names the file first
    return what;
  }
  return "no refusal";
}

TEST(Ktx2Refuse, TruncatedOrPaddedFiles) {
  EXPECT_THAT(refusal("short", [](auto& b) { b.resize(40); }),
              HasSubstr("expected at least 80 bytes (identifier, header and index), got 40 "
                        "(truncated file)"));
  EXPECT_THAT(refusal("cut", [](auto& b) { b.pop_back(); }), HasSubstr("(truncated file)"));
  EXPECT_THAT(refusal("long", [](auto& b) { b.push_back(0); }), HasSubstr("(trailing bytes)"));
  EXPECT_THAT(refusal("empty", [](auto& b) { b.clear(); }), HasSubstr("got 0 (truncated file)"));
}

TEST(Ktx2Refuse, ForgedHeaderFieldsAreNamed) {
  EXPECT_THAT(refusal("magic", [](auto& b) { b[1] = 'X'; }),
              HasSubstr("expected the KTX2 identifier"));
  EXPECT_THAT(refusal("format", [](auto& b) { put_u32_at(b, 12, 43); }),
              HasSubstr("expected a vkFormat among R8_UNORM (9), "));
  EXPECT_THAT(refusal("typesize", [](auto& b) { put_u32_at(b, 16, 4); }),
              HasSubstr("expected typeSize 1 for R8G8B8A8_UNORM, got 4"));
  EXPECT_THAT(refusal("cube", [](auto& b) { put_u32_at(b, 36, 6); }),
              HasSubstr("expected square 2D faces for a cube map, got 8x4x0"));
  EXPECT_THAT(refusal("faces", [](auto& b) { put_u32_at(b, 36, 2); }),
              HasSubstr("expected faceCount 1 or 6 (a cube map), got 2"));
  EXPECT_THAT(refusal("levels0", [](auto& b) { put_u32_at(b, 40, 0); }),
              HasSubstr("expected levelCount from 1 to 4, got 0"));
  EXPECT_THAT(refusal("levels9", [](auto& b) { put_u32_at(b, 40, 9); }),
              HasSubstr("expected levelCount from 1 to 4 for 8x4x0, got 9"));
  EXPECT_THAT(refusal("zstd", [](auto& b) { put_u32_at(b, 44, 2); }),
              HasSubstr("expected supercompressionScheme 0 (none), got 2"));
  EXPECT_THAT(refusal("wide", [](auto& b) { put_u32_at(b, 20, 100000); }),
              HasSubstr("expected pixelWidth from 1 to 16384 for a 2D texture, got 100000"));
  EXPECT_THAT(refusal("oned", [](auto& b) { put_u32_at(b, 24, 0); }),
              HasSubstr("expected pixelHeight of at least 1, got 0 (a 1D texture)"));
  EXPECT_THAT(refusal("layers", [](auto& b) { put_u32_at(b, 32, 268435456); }),
              HasSubstr("expected layerCount from 0 to 2048, got 268435456"));
  EXPECT_THAT(refusal("dfdoffset", [](auto& b) { put_u32_at(b, 48, 200); }),
              HasSubstr("expected dfdByteOffset 176 (right after the level index), got 200"));
  EXPECT_THAT(refusal("sgd", [](auto& b) { b[72] = 8; }),
              HasSubstr("expected no supercompression global data"));
}

TEST(Ktx2Refuse, ForgedLevelIndexDescriptorAndKeyValues) {
  EXPECT_THAT(refusal("leveloffset", [](auto& b) { b[80] += 4; }),
              HasSubstr("level 0: expected byteOffset "));
  // The descriptor's first sample: bitLength 8 -> 16.
  EXPECT_THAT(refusal("sample", [](auto& b) { b[176 + 28 + 2] = 15; }),
              HasSubstr("data format descriptor does not describe R8G8B8A8_UNORM: sample 0: "
                        "expected {bitOffset 0, bitLength 8,"));
  EXPECT_THAT(refusal("srgb", [](auto& b) { b[176 + 14] = 2; }),
              HasSubstr("transferFunction: expected 1 (linear), got 2"));
  EXPECT_THAT(refusal("model", [](auto& b) { b[176 + 12] = 2; }),
              HasSubstr("colorModel: expected 1 (RGBSDA), got 2 (unknown)"));
  EXPECT_THAT(refusal("dfdsize", [](auto& b) { put_u32_at(b, 176, 12); }),
              HasSubstr("expected dfdTotalSize equal to dfdByteLength 92, got 12"));
  // The first key/value entry: KTXorientation.
  EXPECT_THAT(refusal("kvlength", [](auto& b) { put_u32_at(b, 268, 100000); }),
              HasSubstr("key/value data: expected keyAndValueByteLength from 2 to "));
  EXPECT_THAT(refusal("orientation", [](auto& b) { b[268 + 4 + 15 + 1] = 'u'; }),
              HasSubstr("expected KTXorientation \"rd\" (first texel top-left), got \"ru\""));
  EXPECT_THAT(
      refusal("order", [](auto& b) { b[268 + 4] = 'Z'; }),
      HasSubstr("expected keys sorted and unique, got \"KTXwriter\" after \"ZTXorientation\""));
}

TEST(Ktx2Refuse, NonZeroMipPadding) {
  // R16_SFLOAT 5x3: level 2 (one 2-byte texel) comes first, then 2 bytes of
  // padding up to the next multiple of lcm(2, 4) = 4.
  const std::string path = tmp("forged", "padding.ktx2");
  write_ktx2(path, chain(5, 3, 1, 1, 1, Ktx2Encoding::half, true), Ktx2Format::R16_SFLOAT);
  std::vector<uint8_t> b = read_bytes(path);
  const uint64_t level2 = u64_at(b, 80 + 2 * 24);
  ASSERT_EQ(u64_at(b, 80 + 24), level2 + 4);
  b[level2 + 3] = 7;
  write_bytes(path, b);
  try {
    read_ktx2(path);
    ADD_FAILURE() << "no refusal";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(fmt::format("expected zero mipPadding at bytes {} to {}, got "
                                                "0x07 at {}",
                                                level2 + 2, level2 + 4, level2 + 3)));
  }
}

TEST(Ktx2Refuse, InfoAndCheckTilingReportTheReadersMessage) {
  const std::string path = tmp("cli", "cut.ktx2");
  write_ktx2(path, chain(8, 4, 1, 1, 4, Ktx2Encoding::unorm8, false), Ktx2Format::R8G8B8A8_UNORM);
  fs::resize_file(path, fs::file_size(path) - 1);
  const auto r = test::run_skybake({"info", path});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_THAT(r.err, HasSubstr("(truncated file)"));
}

TEST(Ktx2FormatName, RoundTripsAndSuggests) {
  for (const Ktx2FormatInfo& f : ktx2_formats()) {
    EXPECT_EQ(ktx2_format_from_name(f.name), f.format);
    EXPECT_EQ(ktx2_format_from_name(std::string("VK_FORMAT_") + f.name), f.format);
  }
  try {
    ktx2_format_from_name("R16G16B16A16_FLOAT", "ktx2_format");
    ADD_FAILURE() << "no refusal";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ktx2_format: expected one of R8_UNORM, "));
    EXPECT_THAT(e.what(), HasSubstr("(did you mean \"R16G16B16A16_SFLOAT\"?)"));
  }
}

}  // namespace
}  // namespace skybake

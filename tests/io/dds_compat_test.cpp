// Tests for the engine-facing parts of io/dds.hpp: block-compressed files
// (header fields and data order from Microsoft's "DDS_HEADER" and
// "Programming Guide for DDS", every mip level and depth slice where the
// guide puts it), the alpha mode of the DX10 header, the legacy (pre-DX10)
// header of every format that has one, and Pillow (Debian python3-pil) as an
// independent reader of our legacy RGBA8, R8 and BC files.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "io/dds.hpp"
#include "support/file_bytes.hpp"
#include "support/pillow.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::read_bytes;
using test::u32_at;

// A fresh scratch folder per test.
std::string scratch_dir() { return test::test_dir("dds_compat").string(); }

// Smooth deterministic values in [0, 1]: a sum of sines, so that 4x4 blocks
// are not white noise (block formats are judged on data like ours).
Texture smooth(int w, int h, int d, int channels) {
  const std::vector<std::string> names = {"R", "G", "B", "A"};
  Texture t(w, h, d, 1, {names.begin(), names.begin() + channels});
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c)
          t.texel(x, y, z)[c] = 0.5f + 0.45f * std::sin(0.13f * x * (c + 1) + 0.23f * y +
                                                        0.51f * z + 1.3f * c);
  return t;
}

constexpr uint32_t DDSD_CAPS = 0x1, DDSD_HEIGHT = 0x2, DDSD_WIDTH = 0x4, DDSD_PITCH = 0x8;
constexpr uint32_t DDSD_PIXELFORMAT = 0x1000, DDSD_MIPMAPCOUNT = 0x20000;
constexpr uint32_t DDSD_LINEARSIZE = 0x80000, DDSD_DEPTH = 0x800000;
constexpr uint32_t DDPF_ALPHAPIXELS = 0x1, DDPF_FOURCC = 0x4, DDPF_RGB = 0x40;
constexpr uint32_t DDPF_LUMINANCE = 0x20000;
constexpr uint32_t DDSCAPS2_VOLUME = 0x200000;

// ---- block formats ---------------------------------------------------------

TEST(DdsBlock, HeaderHasTheLinearSizeOfTheTopSlice) {
  const std::string path = scratch_dir() + "/bc1.dds";
  // 10x6: 3 x 2 blocks of 8 bytes.
  write_dds(path, {smooth(10, 6, 1, 3)}, DdsFormat::BC1_UNORM);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 8), DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT | DDSD_LINEARSIZE);
  EXPECT_EQ(u32_at(b, 20), 3u * 2u * 8u);
  EXPECT_EQ(u32_at(b, 128), 71u);  // DXGI_FORMAT_BC1_UNORM
  EXPECT_EQ(u32_at(b, 144), 0u);   // BC1 as we write it has no alpha: unknown
  EXPECT_EQ(b.size(), 148u + 48u);
}

// Expected bytes of a volume with mips: for each level, each depth slice
// compressed on its own (Programming Guide for DDS: volume data is mip by mip,
// each mip's slices in order), built here from encode_bc, not the writer.
std::vector<uint8_t> expected_volume_bytes(const std::vector<Texture>& mips, BcFormat format) {
  std::vector<uint8_t> out;
  for (const Texture& m : mips)
    for (int z = 0; z < m.depth; ++z) {
      const std::vector<uint8_t> slice =
          encode_bc(m.texel(0, 0, z), m.width, m.height, m.channel_count(), format);
      EXPECT_EQ(slice.size(), bc_slice_bytes(m.width, m.height, format));
      out.insert(out.end(), slice.begin(), slice.end());
    }
  return out;
}

TEST(DdsBlock, VolumeStoresEveryMipSliceBySliceInBlocks) {
  const std::string path = scratch_dir() + "/bc4.dds";
  // 8x4x4 -> 4x2x2 -> 2x1x1 -> 1x1x1: 2*1*4 + 1*1*2 + 1 + 1 blocks of 8 bytes.
  const std::vector<Texture> mips = build_mip_chain(smooth(8, 4, 4, 1), MipEdge::wrap);
  ASSERT_EQ(mips.size(), 4u);
  write_dds(path, mips, DdsFormat::BC4_UNORM);
  const std::vector<uint8_t> b = read_bytes(path);
  EXPECT_EQ(u32_at(b, 8), DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT |
                              DDSD_LINEARSIZE | DDSD_DEPTH | DDSD_MIPMAPCOUNT);
  EXPECT_EQ(u32_at(b, 20), 16u);  // one top-level slice: 2 x 1 blocks
  EXPECT_EQ(u32_at(b, 28), 4u);
  EXPECT_EQ(b.size(), 148u + (8 + 2 + 1 + 1) * 8u);
  const std::vector<uint8_t> expected = expected_volume_bytes(mips, BcFormat::bc4);
  EXPECT_EQ(std::vector<uint8_t>(b.begin() + 148, b.end()), expected);
}

// Every level and slice reads back as decode_bc gives that slice's blocks
// (the encoding error itself is bounded in block_compression_test.cpp).
TEST(DdsBlock, EveryFormatReadsBackEveryLevelAsTheDecoderGivesIt) {
  const DdsFormat formats[] = {DdsFormat::BC1_UNORM, DdsFormat::BC3_UNORM, DdsFormat::BC4_UNORM,
                               DdsFormat::BC5_UNORM};
  const BcFormat blocks[] = {BcFormat::bc1, BcFormat::bc3, BcFormat::bc4, BcFormat::bc5};
  for (int k = 0; k < 4; ++k) {
    const int nc = dds_component_count(formats[k]);
    const std::vector<Texture> mips = build_mip_chain(smooth(12, 12, 3, nc), MipEdge::wrap);
    const std::string path = scratch_dir() + "/v.dds";
    write_dds(path, mips, formats[k]);
    const DdsImage image = read_dds(path);
    ASSERT_EQ(image.format, formats[k]);
    ASSERT_EQ(image.mips.size(), mips.size());  // 12 -> 6 -> 3 -> 1: four levels
    for (size_t level = 0; level < mips.size(); ++level) {
      const Texture& in = mips[level];
      const Texture& out = image.mips[level];
      ASSERT_EQ(out.width, in.width);
      ASSERT_EQ(out.height, in.height);
      ASSERT_EQ(out.depth, in.depth);
      ASSERT_EQ(out.channel_count(), bc_decoded_channel_count(blocks[k]));
      for (int z = 0; z < in.depth; ++z) {
        const std::vector<uint8_t> slice =
            encode_bc(in.texel(0, 0, z), in.width, in.height, nc, blocks[k]);
        const std::vector<float> decoded = decode_bc(slice.data(), in.width, in.height, blocks[k]);
        const float* got = out.texel(0, 0, z);
        for (size_t i = 0; i < decoded.size(); ++i)
          ASSERT_EQ(got[i], decoded[i]) << dxgi_format_name(formats[k]) << " level " << level;
      }
    }
  }
}

TEST(DdsBlock, AlphaModeIsCustomWhenTheFourthChannelIsData) {
  const std::string dir = scratch_dir();
  write_dds(dir + "/bc3.dds", {smooth(4, 4, 1, 4)}, DdsFormat::BC3_UNORM);
  EXPECT_EQ(u32_at(read_bytes(dir + "/bc3.dds"), 144), 4u);  // DDS_ALPHA_MODE_CUSTOM
  write_dds(dir + "/rgba.dds", {smooth(4, 4, 1, 3)}, DdsFormat::R8G8B8A8_UNORM);
  EXPECT_EQ(u32_at(read_bytes(dir + "/rgba.dds"), 144), 3u);  // alpha left at 1: opaque
  write_dds(dir + "/rg.dds", {smooth(4, 4, 1, 2)}, DdsFormat::R8G8_UNORM);
  EXPECT_EQ(u32_at(read_bytes(dir + "/rg.dds"), 144), 0u);  // no alpha: unknown
}

// ---- legacy headers --------------------------------------------------------

struct Legacy {
  DdsFormat format;
  int channels;
  uint32_t flags, four_cc, bits, r, g, b, a;
};

uint32_t fourcc(const char* s) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}

// Microsoft Learn "Map Direct3D 9 Formats to Direct3D 10" and "DDS_PIXELFORMAT".
const std::vector<Legacy>& legacy_forms() {
  static const std::vector<Legacy> forms = {
      {DdsFormat::R32G32B32A32_FLOAT, 4, DDPF_FOURCC, 116, 0, 0, 0, 0, 0},
      {DdsFormat::R16G16B16A16_FLOAT, 4, DDPF_FOURCC, 113, 0, 0, 0, 0, 0},
      {DdsFormat::R16_FLOAT, 1, DDPF_FOURCC, 111, 0, 0, 0, 0, 0},
      {DdsFormat::R8G8B8A8_UNORM, 4, DDPF_RGB | DDPF_ALPHAPIXELS, 0, 32, 0xff, 0xff00, 0xff0000,
       0xff000000},
      {DdsFormat::R8G8_UNORM, 2, DDPF_RGB, 0, 16, 0xff, 0xff00, 0, 0},
      {DdsFormat::R8_UNORM, 1, DDPF_LUMINANCE, 0, 8, 0xff, 0, 0, 0},
      {DdsFormat::BC1_UNORM, 3, DDPF_FOURCC, fourcc("DXT1"), 0, 0, 0, 0, 0},
      {DdsFormat::BC3_UNORM, 4, DDPF_FOURCC, fourcc("DXT5"), 0, 0, 0, 0, 0},
      {DdsFormat::BC4_UNORM, 1, DDPF_FOURCC, fourcc("ATI1"), 0, 0, 0, 0, 0},
      {DdsFormat::BC5_UNORM, 2, DDPF_FOURCC, fourcc("ATI2"), 0, 0, 0, 0, 0},
  };
  return forms;
}

TEST(DdsLegacy, PixelFormatsAsDocumentedAndNoDx10Header) {
  for (const Legacy& l : legacy_forms()) {
    SCOPED_TRACE(dxgi_format_name(l.format));
    const std::string dir = scratch_dir();
    const std::vector<Texture> mips = build_mip_chain(smooth(8, 8, 2, l.channels), MipEdge::wrap);
    write_dds(dir + "/legacy.dds", mips, l.format, DdsHeader::legacy);
    write_dds(dir + "/dx10.dds", mips, l.format, DdsHeader::dx10);
    const std::vector<uint8_t> legacy = read_bytes(dir + "/legacy.dds");
    const std::vector<uint8_t> dx10 = read_bytes(dir + "/dx10.dds");
    EXPECT_EQ(u32_at(legacy, 80), l.flags);
    EXPECT_EQ(u32_at(legacy, 84), l.four_cc);
    EXPECT_EQ(u32_at(legacy, 88), l.bits);
    EXPECT_EQ(u32_at(legacy, 92), l.r);
    EXPECT_EQ(u32_at(legacy, 96), l.g);
    EXPECT_EQ(u32_at(legacy, 100), l.b);
    EXPECT_EQ(u32_at(legacy, 104), l.a);
    EXPECT_EQ(u32_at(legacy, 112), DDSCAPS2_VOLUME);
    // Same header fields before the pixel format, same data after 128 bytes
    // instead of 148.
    EXPECT_EQ(std::vector<uint8_t>(legacy.begin(), legacy.begin() + 76),
              std::vector<uint8_t>(dx10.begin(), dx10.begin() + 76));
    EXPECT_EQ(std::vector<uint8_t>(legacy.begin() + 128, legacy.end()),
              std::vector<uint8_t>(dx10.begin() + 148, dx10.end()));
    const DdsImage a = read_dds(dir + "/legacy.dds"), b = read_dds(dir + "/dx10.dds");
    EXPECT_EQ(a.format, l.format);
    EXPECT_EQ(a.header, DdsHeader::legacy);
    EXPECT_EQ(b.header, DdsHeader::dx10);
    ASSERT_EQ(a.mips.size(), b.mips.size());
    for (size_t i = 0; i < a.mips.size(); ++i) EXPECT_EQ(a.mips[i].data, b.mips[i].data);
  }
}

TEST(DdsLegacy, BcFourCcAliasesRead) {
  const std::string path = scratch_dir() + "/bc4u.dds";
  write_dds(path, {smooth(4, 4, 1, 1)}, DdsFormat::BC4_UNORM, DdsHeader::legacy);
  const DdsImage ati1 = read_dds(path);
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(84);
  f.write("BC4U", 4);
  f.close();
  const DdsImage bc4u = read_dds(path);
  EXPECT_EQ(bc4u.format, DdsFormat::BC4_UNORM);
  EXPECT_EQ(bc4u.mips[0].data, ati1.mips[0].data);
}

TEST(DdsLegacy, TruncatedAndOversizedLegacyFilesAreRefused) {
  const std::string dir = scratch_dir();
  const std::string path = dir + "/ati1.dds";
  write_dds(path, build_mip_chain(smooth(8, 8, 4, 1), MipEdge::wrap), DdsFormat::BC4_UNORM,
            DdsHeader::legacy);
  const uintmax_t size = fs::file_size(path);
  fs::resize_file(path, size - 1);
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(HasSubstr(
                  "expected 160 bytes of pixel data after the 128-byte header, got 159 (truncated "
                  "file)")));
  // A legacy volume announcing a depth past the 3D limit.
  fs::resize_file(path, size);
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(24);
  const char depth[4] = {0, 0x10, 0, 0};  // 4096
  f.write(depth, 4);
  f.close();
  EXPECT_THAT([&] { read_dds(path); },
              ::testing::ThrowsMessage<IoError>(
                  HasSubstr("expected depth from 1 to 2048 for a volume, got 4096")));
}

TEST(DdsLegacy, FormatsWithoutALegacyFormAndArraysAreRefused) {
  const std::string dir = scratch_dir();
  EXPECT_THAT(
      [&] {
        write_dds(dir + "/p.dds", {smooth(4, 4, 1, 3)}, DdsFormat::R11G11B10_FLOAT,
                  DdsHeader::legacy);
      },
      ::testing::ThrowsMessage<IoError>(HasSubstr(
          "R11G11B10_FLOAT has no legacy (pre-DX10) pixel format; write it with the DX10 header")));
  EXPECT_FALSE(fs::exists(dir + "/p.dds"));
  Texture array(4, 4, 1, 2, {"R"});
  EXPECT_THAT([&] { write_dds(dir + "/a.dds", {array}, DdsFormat::R8_UNORM, DdsHeader::legacy); },
              ::testing::ThrowsMessage<IoError>(
                  HasSubstr("a legacy (pre-DX10) header has no array size, got 2 layers")));
  EXPECT_FALSE(dds_has_legacy_form(DdsFormat::R11G11B10_FLOAT));
  EXPECT_TRUE(dds_has_legacy_form(DdsFormat::BC5_UNORM));
}

// The default header: legacy where it describes the file and common tools
// read it (docs/formats.md "Which tools read which file"), else DX10.
TEST(DdsLegacy, DefaultHeaderIsLegacyForEightBitAndBlockFormatsOfOneTexture) {
  const DdsFormat legacy[] = {DdsFormat::R8G8B8A8_UNORM, DdsFormat::R8_UNORM,
                              DdsFormat::BC1_UNORM,      DdsFormat::BC3_UNORM,
                              DdsFormat::BC4_UNORM,      DdsFormat::BC5_UNORM};
  const DdsFormat dx10[] = {DdsFormat::R32G32B32A32_FLOAT, DdsFormat::R16G16B16A16_FLOAT,
                            DdsFormat::R11G11B10_FLOAT, DdsFormat::R16_FLOAT,
                            DdsFormat::R8G8_UNORM};
  ASSERT_EQ(std::size(legacy) + std::size(dx10), dds_formats().size());
  for (DdsFormat f : legacy) {
    SCOPED_TRACE(dxgi_format_name(f));
    EXPECT_EQ(dds_default_header(f, 1), DdsHeader::legacy);
    EXPECT_TRUE(dds_has_legacy_form(f));
    // A legacy header has no array size: a 2D array keeps DX10.
    EXPECT_EQ(dds_default_header(f, 2), DdsHeader::dx10);
  }
  for (DdsFormat f : dx10) EXPECT_EQ(dds_default_header(f, 1), DdsHeader::dx10) << dxgi_format_name(f);
}

// ---- Pillow, an independent reader -----------------------------------------

// Compares Pillow's 8-bit pixels of `path` with our reader's floats, channel
// by channel, within `tolerance` 8-bit steps (1e-3: the float32 rounding of
// k / 255 * 255).
void expect_pillow_matches(const std::string& path, const std::string& mode, int our_channels,
                           int compared, double tolerance) {
  const test::PillowImage pil = test::pillow_read(path);
  const Texture ours = read_dds(path).mips[0];
  ASSERT_EQ(pil.mode, mode) << path;
  ASSERT_EQ(pil.width, ours.width);
  ASSERT_EQ(pil.height, ours.height);
  const int pil_channels = int(mode.size());
  ASSERT_EQ(pil.bytes.size(), size_t(ours.width) * ours.height * pil_channels);
  for (int t = 0; t < ours.width * ours.height; ++t)
    for (int c = 0; c < compared; ++c)
      ASSERT_NEAR(double(pil.bytes[size_t(t) * pil_channels + c]),
                  double(ours.data[size_t(t) * our_channels + c]) * 255.0, tolerance)
          << path << " texel " << t << " channel " << c;
}

TEST(DdsPillow, LegacyUncompressedFilesMatchOurReaderExactly) {
  const std::string dir = scratch_dir();
  write_dds(dir + "/rgba.dds", {smooth(16, 8, 1, 4)}, DdsFormat::R8G8B8A8_UNORM,
            DdsHeader::legacy);
  expect_pillow_matches(dir + "/rgba.dds", "RGBA", 4, 4, 1e-3);
  write_dds(dir + "/r8.dds", {smooth(16, 8, 1, 1)}, DdsFormat::R8_UNORM, DdsHeader::legacy);
  expect_pillow_matches(dir + "/r8.dds", "L", 1, 1, 1e-3);
  // The DX10 RGBA8 header too, which Pillow also reads.
  write_dds(dir + "/dx10.dds", {smooth(16, 8, 1, 4)}, DdsFormat::R8G8B8A8_UNORM);
  expect_pillow_matches(dir + "/dx10.dds", "RGBA", 4, 4, 1e-3);
}

TEST(DdsPillow, LegacyBlockFilesMatchOurDecoder) {
  // Pillow decodes to 8 bits with integer interpolation; our decoder returns
  // the specification's exact rationals: they agree within one 8-bit step
  // (BC1/BC3 colour also expand RGB565 to 8 bits first: within 1.5 steps).
  const std::string dir = scratch_dir();
  write_dds(dir + "/dxt1.dds", {smooth(16, 12, 1, 3)}, DdsFormat::BC1_UNORM, DdsHeader::legacy);
  expect_pillow_matches(dir + "/dxt1.dds", "RGBA", 4, 4, 1.5);
  write_dds(dir + "/dxt5.dds", {smooth(16, 12, 1, 4)}, DdsFormat::BC3_UNORM, DdsHeader::legacy);
  expect_pillow_matches(dir + "/dxt5.dds", "RGBA", 4, 4, 1.5);
  write_dds(dir + "/ati1.dds", {smooth(16, 12, 1, 1)}, DdsFormat::BC4_UNORM, DdsHeader::legacy);
  expect_pillow_matches(dir + "/ati1.dds", "L", 1, 1, 1.0);
  write_dds(dir + "/ati2.dds", {smooth(16, 12, 1, 2)}, DdsFormat::BC5_UNORM, DdsHeader::legacy);
  expect_pillow_matches(dir + "/ati2.dds", "RGB", 2, 2, 1.0);
}

}  // namespace
}  // namespace skybake

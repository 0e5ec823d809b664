// Tests for io/block_compression.hpp. The decoder against hand-made blocks
// whose palettes are closed forms of the specification (Khronos Data Format
// Specification "S3TC", "RGTC"); the encoder + decoder against closed-form
// cases (a constant block, a two-value block, a ramp) and against bounds that
// follow from the formats on baked noise: for BC4/BC5 a block's RMS error is
// at most that of the 8-level palette spanning the block's range (range/14)
// plus the 8-bit endpoint quantization; for BC1/BC3 colour, at most the
// block's spread around its mean plus the RGB565 quantization.
#include "io/block_compression.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/global_control.h>
#include <gtest/gtest.h>

#include "core/bake_context.hpp"
#include "noise/noise_volume.hpp"

namespace skybake {
namespace {

constexpr BcFormat kAll[] = {BcFormat::bc1, BcFormat::bc3, BcFormat::bc4, BcFormat::bc5};

TEST(BlockCompression, SizesFollowTheBlockGrid) {
  EXPECT_EQ(bc_block_bytes(BcFormat::bc1), 8);
  EXPECT_EQ(bc_block_bytes(BcFormat::bc3), 16);
  EXPECT_EQ(bc_block_bytes(BcFormat::bc4), 8);
  EXPECT_EQ(bc_block_bytes(BcFormat::bc5), 16);
  // ceil(w/4) * ceil(h/4) blocks, at least one per axis.
  EXPECT_EQ(bc_slice_bytes(1, 1, BcFormat::bc1), 8u);
  EXPECT_EQ(bc_slice_bytes(2, 2, BcFormat::bc5), 16u);
  EXPECT_EQ(bc_slice_bytes(5, 3, BcFormat::bc4), 2u * 1u * 8u);
  EXPECT_EQ(bc_slice_bytes(128, 128, BcFormat::bc3), 32u * 32u * 16u);
  EXPECT_EQ(bc_row_pitch(1, BcFormat::bc1), 8u);
  EXPECT_EQ(bc_row_pitch(9, BcFormat::bc3), 48u);
}

// ---- the decoder against the specification -------------------------------

TEST(BcDecoder, Bc4SevenInterpolatedValuesWhenRed0IsLarger) {
  // red0 = 255, red1 = 0; texel i uses index i % 8 (3 bits each, little-endian).
  uint8_t block[8] = {255, 0};
  uint64_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= uint64_t(i % 8) << (3 * i);
  for (int b = 0; b < 6; ++b) block[2 + b] = uint8_t(bits >> (8 * b));
  float out[16];
  decode_bc_block(block, BcFormat::bc4, out);
  const float expected[8] = {1, 0, 6 / 7.0f, 5 / 7.0f, 4 / 7.0f, 3 / 7.0f, 2 / 7.0f, 1 / 7.0f};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(out[i], expected[i % 8], 1e-6f) << i;
}

TEST(BcDecoder, Bc4FiveInterpolatedValuesAndZeroOneOtherwise) {
  uint8_t block[8] = {0, 255};
  uint64_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= uint64_t(7 - i % 8) << (3 * i);
  for (int b = 0; b < 6; ++b) block[2 + b] = uint8_t(bits >> (8 * b));
  float out[16];
  decode_bc_block(block, BcFormat::bc4, out);
  const float palette[8] = {0, 1, 1 / 5.0f, 2 / 5.0f, 3 / 5.0f, 4 / 5.0f, 0, 1};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(out[i], palette[7 - i % 8], 1e-6f) << i;
}

TEST(BcDecoder, Bc5IsTwoBc4BlocksRedThenGreen) {
  uint8_t block[16] = {51, 51, 0, 0, 0, 0, 0, 0, 204, 204, 0, 0, 0, 0, 0, 0};
  float out[32];
  decode_bc_block(block, BcFormat::bc5, out);
  for (int i = 0; i < 16; ++i) {
    EXPECT_FLOAT_EQ(out[2 * i], 51 / 255.0f);
    EXPECT_FLOAT_EQ(out[2 * i + 1], 204 / 255.0f);
  }
}

void put_565(uint8_t* p, int r, int g, int b) {
  const uint16_t c = uint16_t(r << 11 | g << 5 | b);
  p[0] = uint8_t(c), p[1] = uint8_t(c >> 8);
}

TEST(BcDecoder, Bc1FourColoursWhenColor0IsLarger) {
  uint8_t block[8];
  put_565(block, 31, 0, 0);  // red
  put_565(block + 2, 0, 0, 31);  // blue: 0x001f < 0xf800
  const uint32_t bits = 0xE4E4E4E4;  // indices 0, 1, 2, 3 repeating
  for (int b = 0; b < 4; ++b) block[4 + b] = uint8_t(bits >> (8 * b));
  float out[64];
  decode_bc_block(block, BcFormat::bc1, out);
  const float expected[4][4] = {
      {1, 0, 0, 1}, {0, 0, 1, 1}, {2 / 3.0f, 0, 1 / 3.0f, 1}, {1 / 3.0f, 0, 2 / 3.0f, 1}};
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(out[4 * i + c], expected[i % 4][c], 1e-6f);
}

TEST(BcDecoder, Bc1ThreeColoursAndTransparentBlackOtherwise) {
  uint8_t block[8];
  put_565(block, 0, 21, 0);      // 0x02a0
  put_565(block + 2, 31, 63, 0);  // 0xffe0 > 0x02a0
  const uint32_t bits = 0xE4E4E4E4;
  for (int b = 0; b < 4; ++b) block[4 + b] = uint8_t(bits >> (8 * b));
  float out[64];
  decode_bc_block(block, BcFormat::bc1, out);
  const float g0 = 21 / 63.0f;
  const float expected[4][4] = {
      {0, g0, 0, 1}, {1, 1, 0, 1}, {0.5f, (g0 + 1) / 2, 0, 1}, {0, 0, 0, 0}};
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(out[4 * i + c], expected[i % 4][c], 1e-6f);
  // BC3's colour block ignores the order: always four colours, opaque.
  uint8_t bc3[16] = {255, 255, 0, 0, 0, 0, 0, 0};
  std::copy(block, block + 8, bc3 + 8);
  decode_bc_block(bc3, BcFormat::bc3, out);
  EXPECT_NEAR(out[4 * 2 + 1], (2 * g0 + 1) / 3, 1e-6f);
  EXPECT_NEAR(out[4 * 3 + 1], (g0 + 2) / 3, 1e-6f);
  EXPECT_FLOAT_EQ(out[4 * 3 + 3], 1.0f);
}

TEST(BcDecoder, SmallSlicesDropThePadding) {
  // red0 = 128, red1 = 255, every index 0: every texel 128/255.
  const uint8_t block[8] = {128, 255, 0, 0, 0, 0, 0, 0};
  const std::vector<float> out = decode_bc(block, 2, 1, BcFormat::bc4);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0], 128 / 255.0f);
}

// ---- encoder and decoder together ------------------------------------------

std::vector<float> round_trip(const std::vector<float>& texels, int w, int h, int nc,
                              BcFormat format) {
  const std::vector<uint8_t> blocks = encode_bc(texels.data(), w, h, nc, format);
  EXPECT_EQ(blocks.size(), bc_slice_bytes(w, h, format));
  return decode_bc(blocks.data(), w, h, format);
}

TEST(BlockCompression, ConstantBlockDecodesExactly) {
  // Any 8-bit value for the single-channel formats and BC3's alpha; for the
  // colour block, values RGB565 holds exactly (0 and 1).
  for (const BcFormat format : kAll) {
    const int nc = bc_channel_count(format), dc = bc_decoded_channel_count(format);
    const float values[4] = {0.0f, 1.0f, 1.0f, 77 / 255.0f};
    const float single[2] = {77 / 255.0f, 200 / 255.0f};
    const bool colour = format == BcFormat::bc1 || format == BcFormat::bc3;
    std::vector<float> texels;
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < nc; ++c) texels.push_back(colour ? values[c] : single[c]);
    const std::vector<float> out = round_trip(texels, 4, 4, nc, format);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < nc; ++c)
        EXPECT_EQ(out[i * dc + c], texels[i * nc + c]) << bc_format_name(format) << " " << i;
  }
}

TEST(BlockCompression, TwoValueBlockDecodesToItsTwoEndpoints) {
  for (const BcFormat format : kAll) {
    const int nc = bc_channel_count(format), dc = bc_decoded_channel_count(format);
    const bool colour = format == BcFormat::bc1 || format == BcFormat::bc3;
    std::vector<float> texels;
    for (int i = 0; i < 16; ++i) {
      const bool high = (i * 7) % 3 == 0;  // an irregular pattern of the two values
      for (int c = 0; c < nc; ++c) {
        const float lo = colour && c < 3 ? 0.0f : 40 / 255.0f;
        const float hi = colour && c < 3 ? 1.0f : 230 / 255.0f;
        texels.push_back(high ? hi : lo);
      }
    }
    const std::vector<float> out = round_trip(texels, 4, 4, nc, format);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < nc; ++c)
        EXPECT_EQ(out[i * dc + c], texels[i * nc + c]) << bc_format_name(format) << " " << i;
  }
}

TEST(BlockCompression, Bc4RampWithinHalfAPaletteStep) {
  // A horizontal ramp 0..1 over 16 texels: each block spans 3/15 in value, so
  // the 8-level palette's half step is (3/15)/14; the endpoints add at most
  // half an 8-bit step each.
  const int w = 16, h = 8;
  std::vector<float> ramp;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ramp.push_back(float(x) / float(w - 1));
  const std::vector<float> out = round_trip(ramp, w, h, 1, BcFormat::bc4);
  const float bound = (3.0f / 15.0f) / 14.0f + 1.0f / 255.0f;
  for (size_t i = 0; i < ramp.size(); ++i) EXPECT_LE(std::abs(out[i] - ramp[i]), bound) << i;
}

TEST(BlockCompression, OddSizesAndTinyMipsKeepEveryTexel) {
  // 1x1, 2x2 and 5x3: padded to whole blocks, every texel inside decodes.
  for (const auto& [w, h] : {std::pair{1, 1}, {2, 2}, {5, 3}, {3, 7}}) {
    std::vector<float> texels;
    for (int i = 0; i < w * h; ++i) texels.push_back(i % 2 ? 20 / 255.0f : 180 / 255.0f);
    const std::vector<float> out = round_trip(texels, w, h, 1, BcFormat::bc4);
    ASSERT_EQ(out.size(), size_t(w * h));
    for (int i = 0; i < w * h; ++i) EXPECT_EQ(out[i], texels[i]) << w << "x" << h << " " << i;
  }
}

TEST(BlockCompression, ValuesOutsideTheUnitIntervalAreClamped) {
  const std::vector<float> texels(16, 3.0f), negative(16, -2.0f);
  EXPECT_EQ(round_trip(texels, 4, 4, 1, BcFormat::bc4)[5], 1.0f);
  EXPECT_EQ(round_trip(negative, 4, 4, 1, BcFormat::bc4)[5], 0.0f);
}

TEST(BlockCompression, TooManyChannelsIsRefused) {
  const std::vector<float> texels(16 * 3, 0.5f);
  EXPECT_THROW(encode_bc(texels.data(), 4, 4, 3, BcFormat::bc5), std::exception);
}

// The shape noise volume (4 channels) at 32^3: RGBA data as the bake makes it.
Texture shape_noise() {
  NoiseShapeSpec spec;
  spec.size = 32;
  spec.perlin_period = 4;
  spec.perlin_worley = {4, 2};
  spec.worley = {{{4, 2}, {4, 2}, {8, 1}}};
  return bake_noise_shape(spec, BakeContext{});
}

// The texels of `channels` of slice z, interleaved.
std::vector<float> slice_channels(const Texture& t, int z, std::initializer_list<int> channels) {
  std::vector<float> out;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x)
      for (int c : channels) out.push_back(t.texel(x, y, z)[c]);
  return out;
}

double block_rms(const std::vector<float>& a, const std::vector<float>& b, int a_nc, int b_nc,
                 int w, int bx, int by, int c0, int nc) {
  double sse = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const size_t t = size_t(4 * by + j) * w + size_t(4 * bx + i);
      for (int c = c0; c < c0 + nc; ++c) sse += std::pow(double(a[t * a_nc + c]) - b[t * b_nc + c], 2);
    }
  return std::sqrt(sse / (16.0 * nc));
}

TEST(BlockCompression, SingleChannelFormatsOnBakedNoiseStayWithinTheBlockBound) {
  const Texture noise = shape_noise();
  const int n = noise.width;
  for (int z : {0, 13, 31}) {
    const std::vector<float> r = slice_channels(noise, z, {0});
    const std::vector<float> rg = slice_channels(noise, z, {1, 2});
    const std::vector<float> r_out = round_trip(r, n, n, 1, BcFormat::bc4);
    const std::vector<float> rg_out = round_trip(rg, n, n, 2, BcFormat::bc5);
    for (int by = 0; by < n / 4; ++by)
      for (int bx = 0; bx < n / 4; ++bx) {
        // Per channel: RMS <= range/14 + 1/255 (the 8-level palette over the
        // block's range, endpoints rounded to 8 bits), which the encoder's
        // least-squares choice can only beat.
        auto range = [&](const std::vector<float>& v, int nc, int c) {
          float lo = 1, hi = 0;
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
              const float x = v[(size_t(4 * by + j) * n + 4 * bx + i) * nc + c];
              lo = std::min(lo, x), hi = std::max(hi, x);
            }
          return hi - lo;
        };
        EXPECT_LE(block_rms(r, r_out, 1, 1, n, bx, by, 0, 1), range(r, 1, 0) / 14 + 1 / 255.0 + 1e-6);
        for (int c = 0; c < 2; ++c)
          EXPECT_LE(block_rms(rg, rg_out, 2, 2, n, bx, by, c, 1),
                    range(rg, 2, c) / 14 + 1 / 255.0 + 1e-6);
      }
  }
}

TEST(BlockCompression, ColourFormatsOnBakedNoiseStayWithinTheBlockSpread) {
  const Texture noise = shape_noise();
  const int n = noise.width;
  for (int z : {0, 21}) {
    const std::vector<float> rgb = slice_channels(noise, z, {0, 1, 2});
    const std::vector<float> rgba = slice_channels(noise, z, {0, 1, 2, 3});
    const std::vector<float> rgb_out = round_trip(rgb, n, n, 3, BcFormat::bc1);
    const std::vector<float> rgba_out = round_trip(rgba, n, n, 4, BcFormat::bc3);
    for (int by = 0; by < n / 4; ++by)
      for (int bx = 0; bx < n / 4; ++bx) {
        // Spread: RMS distance of the block's colours from their mean, which
        // a fit of every texel to one interpolated colour achieves; RGB565
        // adds at most 1/62 per channel.
        double mean[3] = {}, spread = 0.0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) mean[c] += rgb[(size_t(4 * by + j) * n + 4 * bx + i) * 3 + c] / 16.0;
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c)
              spread += std::pow(rgb[(size_t(4 * by + j) * n + 4 * bx + i) * 3 + c] - mean[c], 2);
        const double bound = std::sqrt(spread / 48.0) + 1 / 62.0 + 1 / 255.0;
        EXPECT_LE(block_rms(rgb, rgb_out, 3, 4, n, bx, by, 0, 3), bound) << bx << "," << by;
        EXPECT_LE(block_rms(rgba, rgba_out, 4, 4, n, bx, by, 0, 3), bound) << bx << "," << by;
      }
    // BC1 is opaque: alpha decodes as 1 everywhere.
    for (size_t t = 0; t < size_t(n) * n; ++t) ASSERT_EQ(rgb_out[t * 4 + 3], 1.0f);
  }
}

TEST(BlockCompression, BytesDoNotDependOnTheThreadCount) {
  const Texture noise = shape_noise();
  const std::vector<float> rgba = slice_channels(noise, 5, {0, 1, 2, 3});
  std::vector<uint8_t> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = encode_bc(rgba.data(), noise.width, noise.height, 4, BcFormat::bc3);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = encode_bc(rgba.data(), noise.width, noise.height, 4, BcFormat::bc3);
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace skybake

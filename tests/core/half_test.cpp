// Tests for core/half.hpp against the bit layouts of IEEE 754 binary16 and of
// the D3D 11-/10-bit unsigned floats (exponent 5 bits, bias 15; mantissa 10,
// 6 and 5 bits). Expected encodings are worked out by hand from the formats.
#include "core/half.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

namespace skybake {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(Half, ExactValues) {
  EXPECT_EQ(half_from_float(0.0f), 0x0000);
  EXPECT_EQ(half_from_float(-0.0f), 0x8000);
  EXPECT_EQ(half_from_float(1.0f), 0x3C00);  // exponent 15 (bias), mantissa 0
  EXPECT_EQ(half_from_float(-2.0f), 0xC000);
  EXPECT_EQ(half_from_float(0.5f), 0x3800);
  EXPECT_EQ(half_from_float(65504.0f), 0x7BFF);                  // largest finite
  EXPECT_EQ(half_from_float(std::ldexp(1.0f, -14)), 0x0400);     // smallest normal
  EXPECT_EQ(half_from_float(std::ldexp(1.0f, -24)), 0x0001);     // smallest subnormal
  EXPECT_EQ(half_from_float(std::ldexp(1023.0f, -24)), 0x03FF);  // largest subnormal
  EXPECT_EQ(half_from_float(1.0f + 1.0f / 1024), 0x3C01);
  EXPECT_EQ(half_from_float(kInf), 0x7C00);
  EXPECT_EQ(half_from_float(-kInf), 0xFC00);
  const uint16_t nan = half_from_float(kNaN);
  EXPECT_EQ(nan & 0x7C00, 0x7C00);
  EXPECT_NE(nan & 0x03FF, 0);
}

TEST(Half, DecodesExactValues) {
  EXPECT_EQ(float_from_half(0x3C00), 1.0f);
  EXPECT_EQ(float_from_half(0xC000), -2.0f);
  EXPECT_EQ(float_from_half(0x7BFF), 65504.0f);
  EXPECT_EQ(float_from_half(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(float_from_half(0x3555), (1.0f + 0x155 / 1024.0f) * 0.25f);  // exp 13, mantissa 0x155
  EXPECT_TRUE(std::signbit(float_from_half(0x8000)));
  EXPECT_EQ(float_from_half(0x7C00), kInf);
  EXPECT_EQ(float_from_half(0xFC00), -kInf);
  EXPECT_TRUE(std::isnan(float_from_half(0x7E00)));
}

TEST(Half, RoundsToNearestEven) {
  const float ulp1 = 1.0f / 1024;  // spacing of halves in [1, 2)
  // Exactly halfway: ties go to the even mantissa.
  EXPECT_EQ(half_from_float(1.0f + 0.5f * ulp1), 0x3C00);  // between ...00 and ...01 -> 00
  EXPECT_EQ(half_from_float(1.0f + 1.5f * ulp1), 0x3C02);  // between ...01 and ...02 -> 02
  EXPECT_EQ(half_from_float(-(1.0f + 1.5f * ulp1)), 0xBC02);
  // Just off the tie goes to the nearer value.
  EXPECT_EQ(half_from_float(std::nextafter(1.0f + 0.5f * ulp1, 2.0f)), 0x3C01);
  EXPECT_EQ(half_from_float(std::nextafter(1.0f + 1.5f * ulp1, 0.0f)), 0x3C01);
  // Rounding carries into the exponent: just under 2 rounds up to 2.0.
  EXPECT_EQ(half_from_float(std::nextafter(2.0f, 0.0f)), 0x4000);
  // Subnormals: 1.5 * 2^-24 ties to 2 units, 0.5 * 2^-24 ties to 0, 2.5 to 2.
  EXPECT_EQ(half_from_float(std::ldexp(1.5f, -24)), 0x0002);
  EXPECT_EQ(half_from_float(std::ldexp(0.5f, -24)), 0x0000);
  EXPECT_EQ(half_from_float(std::nextafter(std::ldexp(0.5f, -24), 1.0f)), 0x0001);
  EXPECT_EQ(half_from_float(std::ldexp(2.5f, -24)), 0x0002);
  // Largest subnormal + half a unit is a tie between 0x03FF (odd) and 0x0400.
  EXPECT_EQ(half_from_float(std::ldexp(1023.5f, -24)), 0x0400);
  // Overflow: 65520 is the tie between 65504 and 2^16 (odd mantissa) -> Inf.
  EXPECT_EQ(half_from_float(65519.0f), 0x7BFF);
  EXPECT_EQ(half_from_float(65520.0f), 0x7C00);
  EXPECT_EQ(half_from_float(1e10f), 0x7C00);
  // binary32 subnormals vanish.
  EXPECT_EQ(half_from_float(std::numeric_limits<float>::denorm_min()), 0x0000);
}

TEST(Half, EveryFinitePatternRoundTrips) {
  int checked = 0;
  for (uint32_t bits = 0; bits < 0x10000; ++bits) {
    if ((bits & 0x7C00) == 0x7C00) continue;  // Inf and NaN
    const float f = float_from_half(uint16_t(bits));
    ASSERT_EQ(half_from_float(f), bits) << "pattern " << bits;
    ++checked;
  }
  EXPECT_EQ(checked, 65536 - 2 * 1024);
}

TEST(Half, DecodingIsMonotonic) {
  // Positive patterns ordered by their bits must decode to increasing values.
  for (uint32_t bits = 1; bits < 0x7C00; ++bits)
    ASSERT_LT(float_from_half(uint16_t(bits - 1)), float_from_half(uint16_t(bits)));
}

TEST(Float11, KnownEncodings) {
  EXPECT_EQ(float11_from_float(1.0f), 15u << 6);  // 0x3C0
  EXPECT_EQ(float11_from_float(2.0f), 16u << 6);
  EXPECT_EQ(float11_from_float(1.5f), (15u << 6) | 32u);
  EXPECT_EQ(float11_from_float(65024.0f), 0x7BFu);  // largest finite: exp 30, mantissa 63
  EXPECT_EQ(float11_from_float(std::ldexp(1.0f, -20)), 0x001u);  // smallest subnormal 2^(-14-6)
  EXPECT_EQ(float11_from_float(std::ldexp(1.0f, -14)), 0x040u);  // smallest normal
  EXPECT_EQ(float11_from_float(0.0f), 0u);
  EXPECT_EQ(float11_from_float(-1.0f), 0u);  // no sign bit: negatives -> 0
  EXPECT_EQ(float11_from_float(-kInf), 0u);
  EXPECT_EQ(float11_from_float(kInf), 0x7C0u);
  const uint32_t nan = float11_from_float(kNaN);
  EXPECT_EQ(nan & 0x7C0u, 0x7C0u);
  EXPECT_NE(nan & 0x3Fu, 0u);
  // Ties to even with a 6-bit mantissa: 1 + 1/128 lies halfway between 1 and 1 + 1/64.
  EXPECT_EQ(float11_from_float(1.0f + 1.0f / 128), 0x3C0u);
  EXPECT_EQ(float11_from_float(1.0f + 3.0f / 128), 0x3C2u);
  EXPECT_EQ(float11_from_float(65535.0f), 0x7C0u);  // past the tie 65280 -> Inf
}

TEST(Float10, KnownEncodings) {
  EXPECT_EQ(float10_from_float(1.0f), 15u << 5);                 // 0x1E0
  EXPECT_EQ(float10_from_float(64512.0f), 0x3DFu);               // exp 30, mantissa 31
  EXPECT_EQ(float10_from_float(std::ldexp(1.0f, -19)), 0x001u);  // smallest subnormal 2^(-14-5)
  EXPECT_EQ(float10_from_float(0.75f), (14u << 5) | 16u);        // 1.1b * 2^-1
  EXPECT_EQ(float10_from_float(1.0f + 1.0f / 64), 0x1E0u);       // tie -> even
  EXPECT_EQ(float10_from_float(-3.0f), 0u);
  EXPECT_EQ(float10_from_float(kInf), 0x3E0u);
}

TEST(SmallFloats, EveryFinitePatternRoundTrips) {
  for (uint32_t bits = 0; bits < 0x7C0; ++bits)
    ASSERT_EQ(float11_from_float(float_from_float11(bits)), bits) << bits;
  for (uint32_t bits = 0; bits < 0x3E0; ++bits)
    ASSERT_EQ(float10_from_float(float_from_float10(bits)), bits) << bits;
  EXPECT_EQ(float_from_float11(0x7BF), 65024.0f);
  EXPECT_EQ(float_from_float10(0x3DF), 64512.0f);
  EXPECT_EQ(float_from_float11(0x7C0), kInf);
  EXPECT_TRUE(std::isnan(float_from_float10(0x3E1)));
}

TEST(R11G11B10, PacksRedLowGreenMiddleBlueHigh) {
  // DXGI_FORMAT_R11G11B10_FLOAT: R bits 0..10, G bits 11..21, B bits 22..31.
  EXPECT_EQ(r11g11b10_from_rgb(1.0f, 0.0f, 0.0f), 0x3C0u);
  EXPECT_EQ(r11g11b10_from_rgb(0.0f, 1.0f, 0.0f), 0x3C0u << 11);
  EXPECT_EQ(r11g11b10_from_rgb(0.0f, 0.0f, 1.0f), 0x1E0u << 22);
  EXPECT_EQ(r11g11b10_from_rgb(2.0f, 0.5f, 0.75f),
            (16u << 6) | ((14u << 6) << 11) | (((14u << 5) | 16u) << 22));
  const Rgb rgb = rgb_from_r11g11b10(r11g11b10_from_rgb(0.25f, 3.0f, 1024.0f));
  EXPECT_EQ(rgb.r, 0.25f);
  EXPECT_EQ(rgb.g, 3.0f);
  EXPECT_EQ(rgb.b, 1024.0f);
}

TEST(R11G11B10, RelativeErrorWithinHalfUlp) {
  // Normal range: relative error at most 2^-7 (11-bit, 6 mantissa bits) and
  // 2^-6 (10-bit, 5 mantissa bits), half an ulp.
  for (float v = 1e-4f; v < 6e4f; v *= 1.0137f) {
    const Rgb rgb = rgb_from_r11g11b10(r11g11b10_from_rgb(v, v, v));
    ASSERT_LE(std::abs(rgb.r - v), v * std::ldexp(1.0f, -7)) << v;
    ASSERT_LE(std::abs(rgb.g - v), v * std::ldexp(1.0f, -7)) << v;
    ASSERT_LE(std::abs(rgb.b - v), v * std::ldexp(1.0f, -6)) << v;
  }
}

}  // namespace
}  // namespace skybake

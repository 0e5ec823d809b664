// check_finite (core/texture.hpp): every finite float passes, including the
// extremes (largest, denormal, negative zero); every NaN and infinity is
// refused wherever it sits, and the message names the first one's texel
// and channel. texture_is_finite and CachedFiniteCheck (core/cached_finite_check.hpp) give
// the same verdict without a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "core/cached_finite_check.hpp"
#include "core/error.hpp"
#include "core/texture.hpp"

namespace skybake {
namespace {

float from_bits(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::string refusal(const Texture& t) {
  try {
    check_finite(t, "out.exr");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckFinite, FiniteExtremesPass) {
  Texture t(37, 3, 2, 1, {"R", "G"});
  const float values[] = {std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::denorm_min(), -0.0f, from_bits(0x7f7fffffu),
                          from_bits(0x007fffffu), 1.0f};
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = values[i % 7];
  EXPECT_EQ(refusal(t), "");
}

TEST(CheckFinite, EveryNonFiniteIsRefusedAtItsTexel) {
  const float bad[] = {std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity(), std::nanf(""),
                       from_bits(0xff800001u), from_bits(0x7fc00abcu)};
  // Before, inside and after whole blocks of a vectorized scan, and last.
  for (float b : bad)
    for (size_t at : {size_t(0), size_t(5), size_t(130), size_t(37 * 3 * 2 * 2 - 1)}) {
      Texture t(37, 3, 2, 1, {"R", "G"});
      t.data[at] = b;
      if (at + 1 < t.data.size()) t.data[at + 1] = b;  // a second one after it
      const std::string message = refusal(t);
      const size_t texel = at / 2;
      const std::string where =
          "x=" + std::to_string(texel % 37) + " y=" + std::to_string(texel / 37 % 3) +
          " z=" + std::to_string(texel / 111) + " layer=0 channel " + (at % 2 ? "G" : "R");
      EXPECT_NE(message.find("out.exr: refusing to write a non-finite value"), std::string::npos)
          << message;
      EXPECT_NE(message.find(where), std::string::npos) << message << " | expected " << where;
    }
}

TEST(CheckFinite, TextureIsFiniteAndFiniteOnceAgree) {
  Texture t(3, 2, 1, 1, {"R", "G", "B"});
  t.data.assign(t.data.size(), 0.5f);
  t.data[4] = std::numeric_limits<float>::denorm_min();
  t.data[5] = -0.0f;
  Texture u = t;
  EXPECT_TRUE(texture_is_finite(t));
  EXPECT_TRUE((CachedFiniteCheck{&t, nullptr})());
  for (uint32_t bits : {0x7f800000u, 0xff800000u, 0x7fc00000u, 0x7f800001u}) {
    u.data[17] = from_bits(bits);
    EXPECT_FALSE(texture_is_finite(u)) << bits;
    const CachedFiniteCheck both{&t, &u};
    EXPECT_FALSE(both());
    EXPECT_FALSE(both());  // remembered
  }
}

}  // namespace
}  // namespace skybake

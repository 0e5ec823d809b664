// Periodic Worley F1 (src/noise/worley.hpp): tiling, range, the 3x3(x3)
// search against a brute-force search of a wider neighbourhood, inversion.
#include "noise/worley.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/math.hpp"

namespace skybake {
namespace {

float dyadic(std::mt19937& rng, float lo, float hi) {
  std::uniform_int_distribution<int> d(int(lo * 1024), int(hi * 1024));
  return float(d(rng)) / 1024.0f;
}

// Nearest feature point over a 5x5x5 block of cells, in double, no clamp.
double brute_force_f1(glm::vec3 p, glm::ivec3 period, uint32_t seed) {
  const glm::ivec3 c(std::floor(p.x), std::floor(p.y), std::floor(p.z));
  double best = 1e9;
  for (int z = -2; z <= 2; ++z)
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        const glm::ivec3 cell = c + glm::ivec3(x, y, z);
        const glm::vec3 o =
            worley3_feature_offset(wrap_index(cell.x, period.x), wrap_index(cell.y, period.y),
                                   wrap_index(cell.z, period.z), seed);
        const double dx = p.x - (cell.x + double(o.x)), dy = p.y - (cell.y + double(o.y)),
                     dz = p.z - (cell.z + double(o.z));
        best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
      }
  return best;
}

TEST(Worley3, RepeatsExactlyWithThePeriodOnEachAxis) {
  std::mt19937 rng(1);
  for (const glm::ivec3 period : {glm::ivec3(1), glm::ivec3(2), glm::ivec3(3, 5, 7)}) {
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 p(dyadic(rng, -12, 12), dyadic(rng, -12, 12), dyadic(rng, -12, 12));
      const float f = worley3_f1(p, period, 5u);
      for (int a = 0; a < 3; ++a)
        for (int k : {-3, -1, 1, 2}) {
          glm::vec3 q = p;
          q[a] += float(k * period[a]);
          ASSERT_EQ(worley3_f1(q, period, 5u), f) << "axis " << a << " k " << k;
        }
    }
  }
}

TEST(Worley3, NegativeCoordinatesUseFloorModulo) {
  for (float x : {-0.125f, -0.75f, -3.5f, -7.875f})
    EXPECT_EQ(worley3_f1({x, x / 2, -x}, glm::ivec3(4), 9u),
              worley3_f1({x + 8, x / 2 + 4, -x - 4}, glm::ivec3(4), 9u))
        << x;
}

TEST(Worley3, EqualsTheClampedNearestDistanceOfAWiderSearch) {
  // The 27-cell search with the bound 1 is exact, not an approximation.
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const glm::ivec3 period(3, 4, 5);
    EXPECT_NEAR(worley3_f1(p, period, 3u), std::min(brute_force_f1(p, period, 3u), 1.0), 1e-6);
  }
}

TEST(Worley3, RangeAndInversion) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 8.0f);
  float lo = 1, hi = 0;
  for (int i = 0; i < 50000; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const float f = worley3_f1(p, glm::ivec3(8), 4u);
    ASSERT_GE(f, 0.0f);
    ASSERT_LE(f, 1.0f);
    ASSERT_EQ(worley3_inverted(p, glm::ivec3(8), 4u), 1.0f - f);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
  EXPECT_LT(lo, 0.1f);
  EXPECT_GT(hi, 0.8f);
}

TEST(Worley3, IsZeroOnAFeaturePointAndTheSeedMatters) {
  const glm::vec3 o = worley3_feature_offset(2, 1, 3, 8u);
  // 2 + o rounds o to 22 bits: zero to that rounding.
  EXPECT_NEAR(worley3_f1(glm::vec3(2, 1, 3) + o, glm::ivec3(4), 8u), 0.0f, 1e-6f);
  EXPECT_NEAR(worley3_inverted(glm::vec3(2, 1, 3) + o, glm::ivec3(4), 8u), 1.0f, 1e-6f);
  EXPECT_NE(worley3_feature_offset(2, 1, 3, 9u), o);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(o[a], 0.0f);
    EXPECT_LT(o[a], 1.0f);
  }
}

TEST(Worley2, RepeatsRangeAndMatchesAWiderSearch) {
  std::mt19937 rng(4);
  const glm::ivec2 period(3, 6);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 p(dyadic(rng, -7, 7), dyadic(rng, -7, 7));
    const float f = worley2_f1(p, period, 2u);
    ASSERT_GE(f, 0.0f);
    ASSERT_LE(f, 1.0f);
    EXPECT_EQ(worley2_f1(p + glm::vec2(3, 0), period, 2u), f);
    EXPECT_EQ(worley2_f1(p - glm::vec2(0, 12), period, 2u), f);
    double best = 1e9;
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        const int cx = int(std::floor(p.x)) + x, cy = int(std::floor(p.y)) + y;
        const glm::vec2 o =
            worley2_feature_offset(wrap_index(cx, period.x), wrap_index(cy, period.y), 2u);
        best = std::min(best, std::hypot(p.x - (cx + double(o.x)), p.y - (cy + double(o.y))));
      }
    EXPECT_NEAR(f, std::min(best, 1.0), 1e-6);
  }
}

}  // namespace
}  // namespace skybake

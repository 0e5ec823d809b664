// Periodic Perlin noise (src/noise/perlin.hpp): tiling of value and gradient
// on every axis (also at negative coordinates), analytic gradient against
// finite differences, and the range.
#include "noise/perlin.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// Random points on a 1/1024 grid: p + period is then exact in float, so a
// correct periodic noise gives bit-identical values there.
float dyadic(std::mt19937& rng, float lo, float hi) {
  std::uniform_int_distribution<int> d(int(lo * 1024), int(hi * 1024));
  return float(d(rng)) / 1024.0f;
}

const glm::ivec3 kPeriods3[] = {{1, 1, 1}, {4, 4, 4}, {3, 5, 7}, {16, 8, 2}};

TEST(Perlin3, RepeatsExactlyWithThePeriodOnEachAxis) {
  std::mt19937 rng(1);
  for (const glm::ivec3 period : kPeriods3) {
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 p(dyadic(rng, -20, 20), dyadic(rng, -20, 20), dyadic(rng, -20, 20));
      const NoiseSample3 n = perlin3_sample(p, period, 7u);
      for (int axis = 0; axis < 3; ++axis) {
        for (int k : {-2, -1, 1, 3}) {
          glm::vec3 q = p;
          q[axis] += float(k * period[axis]);
          const NoiseSample3 m = perlin3_sample(q, period, 7u);
          ASSERT_EQ(m.value, n.value) << "axis " << axis << " k " << k;
          ASSERT_EQ(m.gradient, n.gradient) << "axis " << axis << " k " << k;
        }
      }
    }
  }
}

TEST(Perlin3, ArbitraryPointsRepeatToRounding) {
  // Not dyadic: p + period rounds, so equality holds to float rounding of p.
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    EXPECT_NEAR(perlin3(p + glm::vec3(8, 0, 0), glm::ivec3(8), 3u), perlin3(p, glm::ivec3(8), 3u),
                2e-5);
    EXPECT_NEAR(perlin3(p - glm::vec3(0, 0, 8), glm::ivec3(8), 3u), perlin3(p, glm::ivec3(8), 3u),
                2e-5);
  }
}

TEST(Perlin3, NegativeCoordinatesUseFloorModulo) {
  // Truncating division (C's %) would hash cell -1 as -1 instead of period - 1
  // and break the repetition at negative coordinates.
  const glm::ivec3 period(5);
  for (float x : {-0.25f, -1.5f, -4.75f, -5.125f}) {
    const glm::vec3 p(x, -0.5f - x, 0.375f);
    EXPECT_EQ(perlin3(p, period, 11u), perlin3(p + glm::vec3(10, 5, 0), period, 11u)) << x;
  }
}

TEST(Perlin3, IsNotTrivial) {
  // A period-4 noise must not already repeat with period 1 nor be constant.
  std::mt19937 rng(3);
  int differ = 0;
  double sum2 = 0;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 p(dyadic(rng, 0, 4), dyadic(rng, 0, 4), dyadic(rng, 0, 4));
    const float n = perlin3(p, glm::ivec3(4), 5u);
    differ += std::abs(n - perlin3(p + glm::vec3(1, 0, 0), glm::ivec3(4), 5u)) > 1e-3f;
    sum2 += double(n) * n;
  }
  EXPECT_GT(differ, 150);
  EXPECT_GT(std::sqrt(sum2 / 200), 0.1);
}

TEST(Perlin3, AnalyticGradientMatchesCentralDifferences) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-6.0f, 6.0f);
  const float h = 1.0f / 512.0f;
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const NoiseSample3 n = perlin3_sample(p, glm::ivec3(6, 4, 3), 9u);
    for (int a = 0; a < 3; ++a) {
      glm::vec3 e(0.0f);
      e[a] = h;
      const float fd =
          (perlin3(p + e, glm::ivec3(6, 4, 3), 9u) - perlin3(p - e, glm::ivec3(6, 4, 3), 9u)) /
          (2 * h);
      // Truncation h^2/6 |n'''| (|n'''| < 100) plus rounding 1e-7 / h.
      EXPECT_NEAR(fd, n.gradient[a], 2e-3) << "axis " << a;
    }
  }
}

TEST(Perlin3, GradientIsContinuousAcrossTheWrap) {
  // A central difference that takes its left sample one period away (P - h
  // instead of -h) must still give the derivative at 0: value and gradient
  // join up across the wrapped face.
  const glm::ivec3 period(4, 4, 4);
  const float h = 1.0f / 1024.0f;
  std::mt19937 rng(5);
  for (int i = 0; i < 200; ++i) {
    for (int a = 0; a < 3; ++a) {
      glm::vec3 p(dyadic(rng, 0, 4), dyadic(rng, 0, 4), dyadic(rng, 0, 4));
      p[a] = 0.0f;
      glm::vec3 right = p, left = p;
      right[a] = h;
      left[a] = float(period[a]) - h;
      const float across = (perlin3(right, period, 2u) - perlin3(left, period, 2u)) / (2 * h);
      EXPECT_NEAR(across, perlin3_sample(p, period, 2u).gradient[a], 2e-3);
    }
  }
}

TEST(Perlin3, StaysWithinItsRange) {
  // |g . d| <= 2 for an edge gradient, so |n| <= 2 is proven; the maximum is
  // 1, at a cell centre whose 8 gradients all point at it.
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.0f, 32.0f);
  float lo = 0, hi = 0;
  for (int i = 0; i < 200000; ++i) {
    const float n = perlin3({u(rng), u(rng), u(rng)}, glm::ivec3(32), uint32_t(i % 7));
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  EXPECT_GE(lo, -1.0f - 1e-5f);
  EXPECT_LE(hi, 1.0f + 1e-5f);
  EXPECT_LT(lo, -0.6f);  // and the range is used
  EXPECT_GT(hi, 0.6f);
}

TEST(Perlin3, ValueIsZeroOnLatticePoints) {
  // Gradient noise: every corner term vanishes at its own corner.
  for (int x = -3; x < 3; ++x) EXPECT_EQ(perlin3(glm::vec3(x, 2 * x, -x), glm::ivec3(4), 1u), 0.0f);
}

TEST(Perlin2, RepeatsAndIsContinuousAcrossTheWrap) {
  std::mt19937 rng(7);
  const glm::ivec2 period(3, 8);
  const float h = 1.0f / 1024.0f;
  for (int i = 0; i < 300; ++i) {
    const glm::vec2 p(dyadic(rng, -9, 9), dyadic(rng, -9, 9));
    const NoiseSample2 n = perlin2_sample(p, period, 4u);
    for (int a = 0; a < 2; ++a) {
      glm::vec2 q = p;
      q[a] -= float(2 * period[a]);
      const NoiseSample2 m = perlin2_sample(q, period, 4u);
      ASSERT_EQ(m.value, n.value);
      ASSERT_EQ(m.gradient, n.gradient);
      glm::vec2 at0 = p, right = p, left = p;
      at0[a] = 0.0f;
      right[a] = h;
      left[a] = float(period[a]) - h;
      EXPECT_NEAR((perlin2(right, period, 4u) - perlin2(left, period, 4u)) / (2 * h),
                  perlin2_sample(at0, period, 4u).gradient[a], 2e-3);
    }
  }
}

TEST(Perlin2, AnalyticGradientAndRange) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0.0f, 16.0f);
  const float h = 1.0f / 512.0f;
  float hi = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec2 p(u(rng), u(rng));
    const NoiseSample2 n = perlin2_sample(p, glm::ivec2(16), 6u);
    hi = std::max(hi, std::abs(n.value));
    if (i % 100) continue;
    for (int a = 0; a < 2; ++a) {
      glm::vec2 e(0.0f);
      e[a] = h;
      EXPECT_NEAR(
          (perlin2(p + e, glm::ivec2(16), 6u) - perlin2(p - e, glm::ivec2(16), 6u)) / (2 * h),
          n.gradient[a], 2e-3);
    }
  }
  EXPECT_LE(hi, 1.0f + 1e-5f);
  EXPECT_GT(hi, 0.6f);
}

}  // namespace
}  // namespace skybake

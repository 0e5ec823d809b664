// fBm sums (src/noise/fbm.hpp): every octave count tiles with the base period,
// the Worley weights are Schneider's and sum to 1, ranges, fBm gradients.
#include "noise/fbm.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace skybake {
namespace {

float dyadic(std::mt19937& rng, float lo, float hi) {
  std::uniform_int_distribution<int> d(int(lo * 1024), int(hi * 1024));
  return float(d(rng)) / 1024.0f;
}

TEST(WorleyFbmWeight, SchneidersTableAndSumToOne) {
  EXPECT_EQ(worley_fbm_weight(0, 3), 0.625f);
  EXPECT_EQ(worley_fbm_weight(1, 3), 0.25f);
  EXPECT_EQ(worley_fbm_weight(2, 3), 0.125f);
  EXPECT_EQ(worley_fbm_weight(0, 1), 1.0f);
  for (int n = 1; n <= kMaxOctaves; ++n) {
    float sum = 0;
    for (int o = 0; o < n; ++o) {
      EXPECT_GT(worley_fbm_weight(o, n), 0.0f);
      if (o > 0) {
        EXPECT_LT(worley_fbm_weight(o, n), worley_fbm_weight(o - 1, n));
      }
      sum += worley_fbm_weight(o, n);
    }
    EXPECT_FLOAT_EQ(sum, 1.0f) << n << " octaves";
  }
}

TEST(Fbm3, EveryOctaveCountRepeatsWithTheBasePeriod) {
  std::mt19937 rng(1);
  const glm::ivec3 period(2, 3, 4);
  for (int octaves = 1; octaves <= kMaxOctaves; ++octaves) {
    for (int i = 0; i < 40; ++i) {
      const glm::vec3 p(dyadic(rng, -6, 6), dyadic(rng, -6, 6), dyadic(rng, -6, 6));
      const NoiseSample3 perlin = perlin_fbm3_sample(p, period, octaves, 12u);
      const float worley = worley_fbm3(p, period, octaves, 12u);
      for (int a = 0; a < 3; ++a) {
        for (int k : {-1, 1}) {
          glm::vec3 q = p;
          q[a] += float(k * period[a]);
          const NoiseSample3 m = perlin_fbm3_sample(q, period, octaves, 12u);
          ASSERT_EQ(m.value, perlin.value) << octaves << " octaves, axis " << a;
          ASSERT_EQ(m.gradient, perlin.gradient) << octaves << " octaves, axis " << a;
          ASSERT_EQ(worley_fbm3(q, period, octaves, 12u), worley) << octaves << " octaves";
        }
      }
    }
  }
}

TEST(Fbm2, EveryOctaveCountRepeatsWithTheBasePeriod) {
  std::mt19937 rng(2);
  const glm::ivec2 period(5, 2);
  for (int octaves = 1; octaves <= kMaxOctaves; ++octaves) {
    for (int i = 0; i < 40; ++i) {
      const glm::vec2 p(dyadic(rng, -6, 6), dyadic(rng, -6, 6));
      for (int a = 0; a < 2; ++a) {
        glm::vec2 q = p;
        q[a] -= float(period[a]);
        ASSERT_EQ(perlin_fbm2(q, period, octaves, 3u), perlin_fbm2(p, period, octaves, 3u));
        ASSERT_EQ(worley_fbm2(q, period, octaves, 3u), worley_fbm2(p, period, octaves, 3u));
      }
    }
  }
}

TEST(Fbm3, OctavesAddDetailThatDoesNotTileWithAShorterPeriod) {
  // The second octave must be a new field: with 2 octaves the sum differs from
  // the single octave, and it does not repeat after half the base period.
  std::mt19937 rng(3);
  int changed = 0, half_period_repeats = 0;
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 p(dyadic(rng, 0, 4), dyadic(rng, 0, 4), dyadic(rng, 0, 4));
    changed += worley_fbm3(p, glm::ivec3(4), 2, 1u) != worley_fbm3(p, glm::ivec3(4), 1, 1u);
    half_period_repeats += std::abs(perlin_fbm3(p + glm::vec3(2, 0, 0), glm::ivec3(4), 3, 1u) -
                                    perlin_fbm3(p, glm::ivec3(4), 3, 1u)) < 1e-4f;
  }
  EXPECT_GT(changed, 90);
  EXPECT_LT(half_period_repeats, 10);
}

TEST(Fbm3, RangesAndGradient) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 8.0f);
  const float h = 1.0f / 2048.0f;
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const float w = worley_fbm3(p, glm::ivec3(8), 3, 7u);
    ASSERT_GE(w, 0.0f);
    ASSERT_LE(w, 1.0f);
    const NoiseSample3 n = perlin_fbm3_sample(p, glm::ivec3(8), 4, 7u);
    ASSERT_LE(std::abs(n.value), 1.0f + 1e-5f);  // a weighted mean of |n| <= 1 octaves
    if (i % 50) continue;
    for (int a = 0; a < 3; ++a) {
      glm::vec3 e(0.0f);
      e[a] = h;
      const float fd =
          (perlin_fbm3(p + e, glm::ivec3(8), 4, 7u) - perlin_fbm3(p - e, glm::ivec3(8), 4, 7u)) /
          (2 * h);
      // The finest octave is 8x faster: truncation (8h)^2 / 6 * 100 plus rounding.
      EXPECT_NEAR(fd, n.gradient[a], 5e-3 * (1.0f + std::abs(n.gradient[a])));
    }
  }
}

}  // namespace
}  // namespace skybake

// Perlin-Worley remap variants (src/noise/perlin_worley.hpp): ranges, the
// defining property of each variant, names.
#include "noise/perlin_worley.hpp"

#include <gtest/gtest.h>

namespace skybake {
namespace {

constexpr PerlinWorleyRemap kAll[] = {PerlinWorleyRemap::worley_new_min,
                                      PerlinWorleyRemap::worley_old_min, PerlinWorleyRemap::dilate};

TEST(PerlinWorley, AllVariantsStayInUnitRangeAndGrowWithPerlin) {
  for (PerlinWorleyRemap r : kAll) {
    for (int wi = 0; wi <= 20; ++wi) {
      const float w = wi / 20.0f;
      float previous = -1.0f;
      for (int pi = -30; pi <= 30; ++pi) {  // includes Perlin values past +-1
        const float v = perlin_worley(pi / 25.0f, w, r);
        ASSERT_GE(v, 0.0f) << remap_name(r);
        ASSERT_LE(v, 1.0f) << remap_name(r);
        ASSERT_GE(v, previous) << remap_name(r);
        previous = v;
      }
    }
  }
}

TEST(PerlinWorley, NewMinimumLiftsTheFloorToTheWorleyValue) {
  // remap(p, 0, 1, w, 1): p = 0 gives w, p = 1 gives 1.
  for (float w : {0.0f, 0.3f, 0.9f}) {
    EXPECT_FLOAT_EQ(perlin_worley(-1.0f, w, PerlinWorleyRemap::worley_new_min), w);
    EXPECT_FLOAT_EQ(perlin_worley(1.0f, w, PerlinWorleyRemap::worley_new_min), 1.0f);
    EXPECT_FLOAT_EQ(perlin_worley(0.0f, w, PerlinWorleyRemap::worley_new_min), w + 0.5f * (1 - w));
  }
}

TEST(PerlinWorley, OldMinimumCarvesBelowTheWorleyValue) {
  // remap(p, w, 1, 0, 1): p <= w gives 0, p = 1 gives 1.
  EXPECT_EQ(perlin_worley(0.0f, 0.6f, PerlinWorleyRemap::worley_old_min), 0.0f);        // p01 = 0.5
  EXPECT_FLOAT_EQ(perlin_worley(0.6f, 0.6f, PerlinWorleyRemap::worley_old_min), 0.5f);  // 0.8
  EXPECT_FLOAT_EQ(perlin_worley(1.0f, 0.6f, PerlinWorleyRemap::worley_old_min), 1.0f);
  EXPECT_EQ(perlin_worley(1.0f, 1.0f, PerlinWorleyRemap::worley_old_min), 0.0f);  // empty range
}

TEST(PerlinWorley, DilateUsesTheNegativeOldMinimum) {
  // remap(p, -(1 - w), 1, 0, 1) = (p + 1 - w) / (2 - w).
  EXPECT_FLOAT_EQ(perlin_worley(-1.0f, 0.0f, PerlinWorleyRemap::dilate), 0.5f);
  EXPECT_FLOAT_EQ(perlin_worley(-1.0f, 1.0f, PerlinWorleyRemap::dilate), 0.0f);
  EXPECT_FLOAT_EQ(perlin_worley(1.0f, 0.5f, PerlinWorleyRemap::dilate), 1.0f);
  EXPECT_FLOAT_EQ(perlin_worley(0.0f, 0.5f, PerlinWorleyRemap::dilate), 1.0f / 1.5f);
}

TEST(PerlinWorley, NamesRoundTrip) {
  for (PerlinWorleyRemap r : kAll) EXPECT_EQ(remap_from_name(remap_name(r)), r);
  EXPECT_FALSE(remap_from_name("worley").has_value());
}

}  // namespace
}  // namespace skybake

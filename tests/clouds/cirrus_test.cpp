// High-altitude templates: tile on both axes, values in [0, 1], the exact
// fraction of texels above zero per channel, the stretch of the streaks
// along x, and identical output for 1 and 2 threads.
#include <gtest/gtest.h>

#include <cmath>

#include <tbb/global_control.h>

#include "clouds/cirrus.hpp"
#include "clouds/field_stats.hpp"
#include "core/tiling.hpp"

namespace skybake {
namespace {

CirrusSpec small(int w, int h, uint32_t seed) {
  CirrusSpec s;
  s.width = w;
  s.height = h;
  s.seed = seed;
  return s;
}

Texture bake(const CirrusSpec& s, int threads = 2) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return bake_cirrus(s, BakeContext{});
}

TEST(Cirrus, TilesOnBothAxes) {
  for (uint32_t seed : {0u, 9u}) {
    const Texture t = bake(small(256, 256, seed));
    const TilingReport r = measure_tiling(t, 0.1);
    EXPECT_TRUE(r.tiles) << "seed " << seed << " worst ratio " << r.worst_ratio;
    EXPECT_EQ(r.axes.size(), 6u);
  }
}

TEST(Cirrus, ValuesInUnitRangeWithTheExactCoverage) {
  CirrusSpec s = small(128, 96, 1);
  s.streaks.coverage = 0.3;
  s.cirrocumulus.coverage = 0.55;
  s.altostratus.coverage = 1.0;
  const Texture t = bake(s);
  ASSERT_EQ(t.channels, (std::vector<std::string>{"R", "G", "B"}));
  const double coverage[3] = {0.3, 0.55, 1.0};
  for (int c = 0; c < 3; ++c) {
    size_t above = 0;
    float top = 0.0f;
    for (size_t i = 0; i < t.texel_count(); ++i) {
      const float v = t.data[i * 3 + c];
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
      above += v > 0.0f;
      top = std::max(top, v);
    }
    EXPECT_EQ(top, 1.0f) << c;
    const size_t want = texels_from_fraction(coverage[c], t.texel_count());
    // coverage 1: every texel but the minimum.
    EXPECT_EQ(above, want == t.texel_count() ? want - 1 : want) << "channel " << c;
  }
}

TEST(Cirrus, ZeroCoverageIsAnEmptyChannel) {
  CirrusSpec s = small(64, 64, 2);
  s.cirrocumulus.coverage = 0.0;
  const Texture t = bake(s);
  for (size_t i = 0; i < t.texel_count(); ++i) ASSERT_EQ(t.data[i * 3 + 1], 0.0f);
}

// Mean |difference| between neighbours along x and along y of channel c.
std::pair<double, double> mean_steps(const Texture& t, int c) {
  double dx = 0.0, dy = 0.0;
  for (int y = 0; y + 1 < t.height; ++y)
    for (int x = 0; x + 1 < t.width; ++x) {
      dx += std::abs(t.at(x + 1, y, 0, 0, c) - t.at(x, y, 0, 0, c));
      dy += std::abs(t.at(x, y + 1, 0, 0, c) - t.at(x, y, 0, 0, c));
    }
  return {dx, dy};
}

TEST(Cirrus, StreaksRunAlongXAndCellsAreIsotropic) {
  CirrusSpec s = small(256, 256, 3);
  s.streaks = {{2, 16}, 3, 0.6};
  const Texture t = bake(s);
  const auto [sx, sy] = mean_steps(t, 0);
  EXPECT_LT(sx * 3.0, sy) << "8:1 stretch: values change far less along x";
  const auto [cx, cy] = mean_steps(t, 1);
  EXPECT_NEAR(cx / cy, 1.0, 0.2);
}

TEST(Cirrus, SameForOneAndTwoThreadsAndSeedsDiffer) {
  const Texture one = bake(small(128, 128, 4), 1);
  const Texture two = bake(small(128, 128, 4), 2);
  EXPECT_TRUE(one.data == two.data);
  EXPECT_FALSE(bake(small(128, 128, 5)).data == two.data);
}

TEST(Cirrus, SpecRulesNameTheField) {
  CirrusSpec s;
  EXPECT_TRUE(spec_problems(s).empty());
  s.cirrocumulus.period = {4, 0};
  s.altostratus.coverage = 1.5;
  const auto p = spec_problems(s);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].field, "cirrocumulus.period[1]");
  EXPECT_EQ(p[1].field, "altostratus.coverage");
}

TEST(FieldStats, KthLargestAndTopFraction) {
  EXPECT_EQ(kth_largest({3.0f, 1.0f, 2.0f, 5.0f}, 1), 5.0f);
  EXPECT_EQ(kth_largest({3.0f, 1.0f, 2.0f, 5.0f}, 4), 1.0f);
  TexelVector v = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f};
  keep_top_fraction(v, 0.4);  // 2 of 5 above zero: q = 2, max = 4
  EXPECT_EQ(v, (TexelVector{0.0f, 0.0f, 0.0f, 0.5f, 1.0f}));
  EXPECT_EQ(octaves_within_size(4, 8, 64), 4);  // 4, 8, 16, 32 cells: 2 texels each at 32
  EXPECT_EQ(octaves_within_size(64, 3, 64), 1);
}

}  // namespace
}  // namespace skybake

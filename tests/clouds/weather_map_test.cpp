// The weather map: tiles, every value in [0, 1], the rain rule on every
// texel, the mean coverage equal to the preset's for several coverages and
// seeds, the exact raining area, the type range, the Frostbite layout's type
// coordinate, and identical output for 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <tbb/global_control.h>

#include "clouds/weather_map.hpp"
#include "core/tiling.hpp"

namespace skybake {
namespace {

WeatherSpec stormy(int size, uint32_t seed) {
  WeatherSpec s;
  s.size = size;
  s.seed = seed;
  s.coverage = {0.6, 10.0, 4, 2.5};
  s.precipitation = {0.1, 0.08, 20.0, 3, 0.7};
  s.type = {0.6, 0.3, 25.0, 2};
  return s;
}

Texture bake(const WeatherSpec& s, int threads = 2) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return bake_weather_map(s, BakeContext{});
}

double channel_mean(const Texture& t, int c) {
  double sum = 0.0;
  for (size_t i = 0; i < t.texel_count(); ++i) sum += t.data[i * t.channel_count() + c];
  return sum / double(t.texel_count());
}

TEST(WeatherMap, TilesOnBothAxes) {
  for (uint32_t seed : {0u, 5u}) {
    const Texture t = bake(stormy(256, seed));
    const TilingReport r = measure_tiling(t, 0.1);
    EXPECT_TRUE(r.tiles) << "seed " << seed << " worst ratio " << r.worst_ratio;
    EXPECT_EQ(r.axes.size(), 6u);  // x and y, three channels
  }
}

TEST(WeatherMap, ValuesInUnitRangeAndFinite) {
  const Texture t = bake(stormy(128, 3));
  ASSERT_EQ(t.channels, (std::vector<std::string>{"R", "G", "B"}));
  for (float v : t.data) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
}

TEST(WeatherMap, RainRuleHoldsOnEveryTexel) {
  for (uint32_t seed : {0u, 1u, 42u}) {
    for (double area : {0.02, 0.1, 0.3}) {
      WeatherSpec s = stormy(128, seed);
      s.precipitation.area = area;
      s.coverage.mean = 0.7;
      const Texture t = bake(s);
      size_t raining = 0;
      for (size_t i = 0; i < t.texel_count(); ++i) {
        const float* v = &t.data[i * 3];
        // coverage >= 0.7 p everywhere; at p = 1: coverage >= 0.7, type 1.
        ASSERT_GE(v[0], kRainCoverage * v[1]) << "texel " << i;
        if (v[1] == 1.0f) {
          ++raining;
          ASSERT_GE(v[0], 0.7f) << "texel " << i;
          ASSERT_EQ(v[2], 1.0f) << "texel " << i;
        }
      }
      // Precipitation is 1 on exactly round(area N) texels.
      EXPECT_EQ(raining, size_t(std::lround(area * t.texel_count()))) << seed << " " << area;
    }
  }
}

TEST(WeatherMap, MeanCoverageMatchesThePresetForSeveralCoveragesAndSeeds) {
  for (double coverage : {0.1, 0.5, 0.9}) {
    for (uint32_t seed : {0u, 1u, 99u}) {
      WeatherSpec s = stormy(96, seed);
      s.coverage.mean = coverage;
      s.precipitation.area = 0.05;  // rain floor mean <= 0.7 x 0.13 < 0.1
      const Texture t = bake(s);
      const double mean = channel_mean(t, 0);
      EXPECT_NEAR(mean, coverage, 1e-5) << "coverage " << coverage << " seed " << seed;
      EXPECT_NEAR(meta_double(t.metadata, "coverage.mean_baked"), mean, 1e-12);
    }
  }
}

TEST(WeatherMap, CoverageHitsTheEndsAndHigherContrastSaturatesMore) {
  WeatherSpec s = stormy(64, 2);
  s.precipitation.area = 0.0;
  s.coverage.mean = 0.0;
  EXPECT_EQ(channel_mean(bake(s), 0), 0.0);
  s.coverage.mean = 1.0;
  EXPECT_NEAR(channel_mean(bake(s), 0), 1.0, 1e-6);
  auto saturated = [&](double contrast) {
    s.coverage.mean = 0.4;
    s.coverage.contrast = contrast;
    const Texture t = bake(s);
    size_t n = 0;
    for (size_t i = 0; i < t.texel_count(); ++i)
      n += t.data[i * 3] == 0.0f || t.data[i * 3] == 1.0f;
    return n;
  };
  EXPECT_LT(saturated(1.0), saturated(8.0));
}

TEST(WeatherMap, NoRainMeansNoPrecipitationAndTypeWithinMeanPlusMinusVariation) {
  WeatherSpec s = stormy(96, 8);
  s.precipitation.area = 0.0;
  s.type = {0.4, 0.25, 20.0, 2};
  const Texture t = bake(s);
  float lo = 1.0f, hi = 0.0f;
  for (size_t i = 0; i < t.texel_count(); ++i) {
    ASSERT_EQ(t.data[i * 3 + 1], 0.0f);
    lo = std::min(lo, t.data[i * 3 + 2]);
    hi = std::max(hi, t.data[i * 3 + 2]);
  }
  EXPECT_GE(lo, 0.15f - 1e-6f);
  EXPECT_LE(hi, 0.65f + 1e-6f);
  // The type noise is scaled so its largest |n| is 1: one end is reached.
  EXPECT_TRUE(std::abs(lo - 0.15f) < 1e-6f || std::abs(hi - 0.65f) < 1e-6f) << lo << " " << hi;

  s.type.variation = 0.0;
  const Texture flat = bake(s);
  for (size_t i = 0; i < flat.texel_count(); ++i) ASSERT_EQ(flat.data[i * 3 + 2], 0.4f);
}

TEST(WeatherMap, FrostbiteLayoutIndexesTheCloudTypeColumns) {
  WeatherSpec s = stormy(96, 4);
  s.type_count = 5;
  const Texture schneider = bake(s);
  s.layout = WeatherLayout::frostbite;
  const Texture frostbite = bake(s);
  ASSERT_EQ(frostbite.channels, (std::vector<std::string>{"R", "G"}));
  EXPECT_EQ(meta_string(frostbite.metadata, "weather_layout"), "frostbite");
  size_t raining = 0, dry = 0;
  for (size_t i = 0; i < schneider.texel_count(); ++i) {
    const float* a = &schneider.data[i * 3];
    const float* b = &frostbite.data[i * 2];
    ASSERT_EQ(b[0], a[0]);  // density = coverage
    if (a[1] == 1.0f) {     // raining: the cumulonimbus column (index 3) itself
      ++raining;
      ASSERT_EQ(b[1], float(3.5 / 5));
    } else if (a[1] == 0.0f) {  // dry: index 2 x type (stratus 0, stratocu 1, cumulus 2)
      ++dry;
      ASSERT_NEAR(b[1], (2.0 * a[2] + 0.5) / 5, 1e-6);
    }
  }
  EXPECT_GT(raining, 0u);
  EXPECT_GT(dry, 0u);
}

TEST(WeatherMap, SameForOneAndTwoThreadsAndSeedsDiffer) {
  const Texture one = bake(stormy(128, 6), 1);
  const Texture two = bake(stormy(128, 6), 2);
  EXPECT_TRUE(one.data == two.data);
  EXPECT_EQ(one.metadata, two.metadata);
  EXPECT_FALSE(bake(stormy(128, 7)).data == two.data);
}

TEST(WeatherMap, MetadataRecordsWorldAndTexelSize) {
  WeatherSpec s = stormy(64, 0);
  s.world_size_km = 32.0;
  s.coverage.feature_km = 8.0;
  const Texture t = bake(s);
  EXPECT_EQ(meta_double(t.metadata, "world_size_km"), 32.0);
  EXPECT_EQ(meta_double(t.metadata, "texel_size_m"), 500.0);
  EXPECT_EQ(meta_int(t.metadata, "coverage.period"), 4);
  EXPECT_EQ(meta_string(t.metadata, "weather_layout"), "schneider");
}

TEST(WeatherMap, PeriodFromFeatureSizeAndBack) {
  EXPECT_EQ(period_from_feature_km(60.0, 12.0), 5);
  EXPECT_EQ(period_from_feature_km(60.0, 13.0), 5);   // 4.6 cells -> 5
  EXPECT_EQ(period_from_feature_km(60.0, 500.0), 1);  // at least one cell
  for (int period = 1; period <= 64; ++period)
    EXPECT_EQ(period_from_feature_km(60.0, feature_km_from_period(60.0, period)), period);
}

TEST(WeatherMap, SpecRulesNameTheField) {
  WeatherSpec s;
  EXPECT_TRUE(spec_problems(s).empty());
  s.precipitation.area = 0.5;
  s.precipitation.edge = 0.1;
  s.coverage.mean = 0.3;  // below 0.7 x 0.6
  auto p = spec_problems(s);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].field, "coverage.mean");
  s.coverage.mean = 0.5;
  s.precipitation.edge = 0.6;  // area + edge > 1
  p = spec_problems(s);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p[0].field, "precipitation.edge");
  EXPECT_THROW(bake_weather_map(s, BakeContext{}), std::exception);
}

}  // namespace
}  // namespace skybake

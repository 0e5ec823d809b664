// measure_tiling: a periodic texture passes, a ramp fails on its axis only,
// constants pass, and the ratio is the seam jump over the interior jump.
#include <gtest/gtest.h>

#include <cmath>

#include "core/math.hpp"
#include "core/tiling.hpp"

namespace skybake {
namespace {

TEST(Tiling, PeriodicTextureTilesOnEveryAxis) {
  Texture t(32, 16, 8, 1, {"R", "G"});
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 32; ++x) {
        t.at(x, y, z, 0, 0) = float(std::sin(2 * kPi * x / 32) * std::cos(2 * kPi * y / 16));
        t.at(x, y, z, 0, 1) = float(std::cos(2 * kPi * 2 * z / 8));
      }
  const TilingReport r = measure_tiling(t, 1e-6);  // rounding only
  EXPECT_TRUE(r.tiles) << r.worst_ratio;
  EXPECT_EQ(r.axes.size(), 6u);
}

TEST(Tiling, RampFailsOnItsAxisOnly) {
  Texture t(10, 10, 1, 1, {"R"});
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) t.at(x, y, 0, 0, 0) = float(x);
  const TilingReport r = measure_tiling(t, 0.1);
  EXPECT_FALSE(r.tiles);
  ASSERT_EQ(r.axes.size(), 2u);
  EXPECT_EQ(r.axes[0].axis, 'x');
  EXPECT_FALSE(r.axes[0].tiles);
  EXPECT_DOUBLE_EQ(r.axes[0].ratio, 9.0);  // seam 9, interior 1
  EXPECT_TRUE(r.axes[1].tiles);            // constant along y
  EXPECT_EQ(r.axes[1].ratio, 0.0);
}

TEST(Tiling, LayersAreMeasuredToo) {
  Texture t(8, 8, 1, 2, {"R"});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) t.at(x, y, 0, 1, 0) = float(y);  // layer 1 ramps along y
  EXPECT_FALSE(measure_tiling(t, 0.1).tiles);
}

}  // namespace
}  // namespace skybake

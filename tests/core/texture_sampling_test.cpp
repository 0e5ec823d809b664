// sample_bilinear never reads outside its texture, whatever the coordinates:
// a NaN from degenerate geometry, an infinity or a huge value on a wrapped axis.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/texture_sampling.hpp"

namespace skybake {
namespace {

Texture ramp() {
  Texture t(4, 3, 1, 1, {"R"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i + 1);
  return t;
}

TEST(SampleBilinear, CoordinatesThatAreNotFiniteOrHugeReadTexelsOfTheTexture) {
  const Texture t = ramp();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double u : {nan, inf, -inf, 1e300, -1e300, 0.5})
    for (double v : {nan, inf, -inf, 1e300, -1e300, 0.5})
      for (bool wrap : {false, true}) {
        const double r = sample_bilinear(t, u, v, 0, 0, wrap).x;
        EXPECT_TRUE(r >= 1.0 && r <= 12.0) << u << " " << v << " wrap " << wrap << ": " << r;
      }
  EXPECT_EQ(sample_bilinear(t, nan, nan, 0, 0, false).x, 1.0) << "NaN reads the first texel";
  EXPECT_EQ(sample_bilinear(t, 0.125, 1.0 / 6.0, 0, 0, true).x, 1.0) << "centres unchanged";
  EXPECT_EQ(sample_bilinear(t, 1.125, 1.0 / 6.0, 0, 0, true).x, 1.0) << "one period on";
}

}  // namespace
}  // namespace skybake

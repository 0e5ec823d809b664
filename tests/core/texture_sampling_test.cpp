// sample_bilinear never reads outside its texture, whatever the coordinates:
// a NaN from degenerate geometry, an infinity or a huge value on a wrapped axis;
// and a row read (bilinear_row + sample_bilinear_rgb) is the same read.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

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

// The row read does the v half once and the u half per read; it must give
// sample_bilinear's value exactly, at every v and u (edges, clamps, NaN) and
// on every slice and layer, whatever the channel count beyond three.
TEST(SampleBilinearRgb, IsSampleBilinearBitForBit) {
  for (int channels : {3, 4}) {
    std::vector<std::string> names = {"R", "G", "B", "A"};
    names.resize(size_t(channels));
    Texture t(5, 4, 2, 3, names);
    for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(std::sin(0.37 * double(i)) + 1.1);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double coords[] = {nan, -0.3, 0.0, 0.1, 0.125, 0.33, 0.5, 0.77, 0.9, 1.0, 1.4};
    for (int layer = 0; layer < t.layers; ++layer)
      for (int z = 0; z < t.depth; ++z)
        for (double v : coords) {
          const BilinearRow row = bilinear_row(t, v, z, layer);
          for (double u : coords) {
            const glm::dvec4 a = sample_bilinear(t, u, v, z, layer, false);
            const glm::dvec3 b = sample_bilinear_rgb(t, row, u);
            for (int c = 0; c < 3; ++c)
              EXPECT_EQ(a[c], b[c]) << "u " << u << " v " << v << " z " << z << " layer " << layer;
          }
        }
  }
}

}  // namespace
}  // namespace skybake

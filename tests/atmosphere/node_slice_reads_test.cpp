// The single-precision mu_s taps of the multiple-scattering pass's node loop
// (atmosphere/kernels/node_slice_reads.hpp) against the double mapping; the
// loop itself against one texel at a time is in kernels_test.cpp.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/kernels/node_slice_reads.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

// Cosines across [-1, 1] in fine steps, the edges and values past them.
std::vector<double> cosines(double mu_s_min) {
  std::vector<double> mu = {-1.5, -1.0, -0.0, 0.0, 1.0, 1.5, mu_s_min, std::nextafter(mu_s_min, 0.0),
                            std::nextafter(1.0, 0.0)};
  for (int i = 0; i <= 20000; ++i) mu.push_back(-1.0 + 2.0 * i / 20000.0);
  return mu;
}

// The texel coordinate i0 + w of a tap.
TEST(SunCosineTapsFloat, WithinAFortiethOfAThousandthOfATexelOfTheDoubleMapping) {
  Atmosphere thick = fixtures::earth_atmosphere();
  // A shell 0.8 Rb thick: span = H - d_min < d_min, so k2 < 0 in the mapping.
  thick.top_radius_m = 1.8 * thick.bottom_radius_m;
  for (const Atmosphere& atm :
       {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), thick})
    for (const ScatteringShape& shape :
         {ScatteringShape{}, ScatteringShape{8, 32, 64, 4, -0.5}, ScatteringShape{4, 8, 7, 2, 0.0}}) {
      const MuSAxis axis(atm, shape);
      const SunCosineTapsFloat taps(axis.constants());
      for (double mu_s : cosines(shape.mu_s_min)) {
        const AxisTap exact = axis.tap(mu_s);
        int i0 = -1;
        float w = -1.0f;
        taps.tap(mu_s, i0, w);
        ASSERT_GE(i0, 0);
        ASSERT_LE(i0, shape.mu_s_size - 2);
        ASSERT_GE(w, 0.0f);
        ASSERT_LE(w, 1.0f);
        ASSERT_NEAR(i0 + double(w), exact.i0 + exact.w, 2.5e-5)
            << "mu_s " << mu_s << " top " << atm.top_radius_m << " mu_s_min " << shape.mu_s_min;
      }
    }
}

}  // namespace
}  // namespace skybake

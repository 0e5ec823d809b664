// sample_medium_block (atmosphere/medium_block.hpp) against sample_medium at
// altitudes across every layer of Earth's profiles (the ozone tent's two
// layers and its clamp to 0 included), below the ground and far above the
// top: the same bits with std::exp, within 1e-15 relative with the block's.
#include "atmosphere/medium_block.hpp"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

std::vector<double> altitudes() {
  std::vector<double> h = {-5.0, 0.0, 10e3, 25e3, 40e3, 1e9};
  for (int i = 0; i <= 997; ++i) h.push_back(100.0 * i + 0.37);
  return h;
}

TEST(SampleMediumBlock, SameBitsWithLibmAndWithinABoundWithTheBlock) {
  Atmosphere atm = fixtures::earth_atmosphere();
  // A growing exponential's argument leaves exp_block's range far up.
  atm.components.push_back(fixtures::make_component("grows", glm::dvec3(1e-9), glm::dvec3(0.0),
                                                    {{{0.0, 1e-3, 1e-3, 0.0, 0.0}}}));
  const std::vector<double> h = altitudes();
  MediumBlock libm, block;
  sample_medium_block(atm, h.data(), h.size(), NodeExp::libm, libm);
  sample_medium_block(atm, h.data(), h.size(), NodeExp::block, block);
  for (size_t i = 0; i < h.size(); ++i) {
    const MediumSample s = sample_medium(atm, h[i]);
    EXPECT_EQ(std::memcmp(&s.scattering, &libm.scattering[i], sizeof(glm::dvec3)), 0) << h[i];
    EXPECT_EQ(std::memcmp(&s.extinction, &libm.extinction[i], sizeof(glm::dvec3)), 0) << h[i];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(block.scattering[i][c], s.scattering[c], 1e-15 * s.scattering[c]) << h[i];
      EXPECT_NEAR(block.extinction[i][c], s.extinction[c], 1e-15 * s.extinction[c]) << h[i];
    }
  }
}

}  // namespace
}  // namespace skybake

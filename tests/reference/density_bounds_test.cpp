// Tests of reference/density_bounds.hpp: kinks, maxima and minima of
// density profiles against closed forms.
#include "reference/density_bounds.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(DensityBounds, TentKinks) {
  const auto k = profile_kink_altitudes(tent_profile(10e3, 25e3, 40e3), 100e3);
  ASSERT_EQ(k.size(), 3u);
  EXPECT_NEAR(k[0], 10e3, 1e-9);
  EXPECT_NEAR(k[1], 25e3, 1e-9);
  EXPECT_NEAR(k[2], 40e3, 1e-9);
}

TEST(DensityBounds, SlabKinksAndNoneForExponential) {
  const auto slab = profile_kink_altitudes(uniform_profile(2e3, 5e3), 100e3);
  ASSERT_EQ(slab.size(), 2u);
  EXPECT_EQ(slab[0], 2e3);
  EXPECT_EQ(slab[1], 5e3);
  EXPECT_TRUE(profile_kink_altitudes(exponential_profile(8e3), 100e3).empty());
  // Kinks at or above the top are not inside the shell.
  EXPECT_TRUE(profile_kink_altitudes(uniform_profile(0.0, 100e3), 100e3).empty());
}

// 2 exp(-h / 1000) - 0.5 crosses 1 at h = 1000 ln(4/3) and 0 at 1000 ln 4,
// where the clamp bends it.
TEST(DensityBounds, ClampCrossingsOfAnExponentialLayer) {
  DensityLayer l;
  l.exp_term = 2.0;
  l.exp_scale_per_m = -1e-3;
  l.constant_term = -0.5;
  const auto k = profile_kink_altitudes({{l}}, 100e3);
  ASSERT_EQ(k.size(), 2u);
  EXPECT_NEAR(k[0], 1e3 * std::log(4.0 / 3.0), 1e-9);
  EXPECT_NEAR(k[1], 1e3 * std::log(4.0), 1e-9);
}

// -exp(h / 1000) + 0.002 h + d has its maximum at h* = 1000 ln 2, where it is
// -2 + 2 ln 2 + d; d is chosen to make that 0.5.
DensityProfile concave_profile() {
  DensityLayer l;
  l.exp_term = -1.0;
  l.exp_scale_per_m = 1e-3;
  l.linear_term_per_m = 2e-3;
  l.constant_term = 2.5 - 2.0 * std::log(2.0);
  return {{l}};
}

TEST(DensityBounds, MaximumAtAnInteriorCriticalPoint) {
  const DensityProfile p = concave_profile();
  EXPECT_NEAR(max_density_over(p, 0.0, 3e3), 0.5, 1e-12);
  EXPECT_NEAR(density_at(p, 1e3 * std::log(2.0)), 0.5, 1e-12);
  // Away from h* the maximum is at the end nearer to it.
  EXPECT_NEAR(max_density_over(p, 1e3, 2e3), density_at(p, 1e3), 1e-15);
  // A concave formula has its minimum at an end.
  EXPECT_NEAR(min_density_over(p, 0.0, 3e3), std::min(density_at(p, 0.0), density_at(p, 3e3)),
              1e-15);
}

// A convex formula has its minimum at the critical point: exp(h / 1000) -
// 0.002 h + d, minimum at h* = 1000 ln 2 of 2 - 2 ln 2 + d, made 0.25.
TEST(DensityBounds, MinimumAtAnInteriorCriticalPoint) {
  DensityLayer l;
  l.exp_term = 1.0;
  l.exp_scale_per_m = 1e-3;
  l.linear_term_per_m = -2e-3;
  l.constant_term = 0.25 - 2.0 + 2.0 * std::log(2.0);
  EXPECT_NEAR(min_density_over({{l}}, 0.0, 3e3), 0.25, 1e-12);
}

TEST(DensityBounds, MaximaOfTheUsualProfiles) {
  EXPECT_NEAR(max_density_over(tent_profile(10e3, 25e3, 40e3), 20e3, 30e3), 1.0, 1e-15);
  EXPECT_NEAR(max_density_over(tent_profile(10e3, 25e3, 40e3), 30e3, 35e3), 2.0 / 3.0, 1e-15);
  EXPECT_EQ(max_density_over(tent_profile(10e3, 25e3, 40e3), 41e3, 90e3), 0.0);
  EXPECT_NEAR(max_density_over(exponential_profile(8e3), 1e3, 2e3), std::exp(-1.0 / 8.0), 1e-15);
  EXPECT_EQ(max_density_over(uniform_profile(2e3, 5e3), 0.0, 1e3), 0.0);
  EXPECT_EQ(max_density_over(uniform_profile(2e3, 5e3), 0.0, 3e3), 1.0);
  EXPECT_EQ(max_density_over({}, 0.0, 3e3), 0.0);
  EXPECT_NEAR(min_density_over(tent_profile(10e3, 25e3, 40e3), 20e3, 30e3), 2.0 / 3.0, 1e-15);
  EXPECT_EQ(min_density_over(tent_profile(10e3, 25e3, 40e3), 5e3, 30e3), 0.0);
  EXPECT_NEAR(min_density_over(exponential_profile(8e3), 1e3, 2e3), std::exp(-2.0 / 8.0), 1e-15);
  EXPECT_EQ(min_density_over(uniform_profile(2e3, 5e3), 1e3, 3e3), 0.0);
  EXPECT_EQ(min_density_over(uniform_profile(2e3, 5e3), 2e3, 4e3), 1.0);
}

}  // namespace
}  // namespace skybake

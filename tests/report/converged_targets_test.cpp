// The converged Psi_ms targets of converged_targets_accuracy_test.cpp (see
// there for the models and views) in the unit tier: Mars shrunk to a 10 km
// planet as it is, and Earth's 2 % bar and Mars' 8 % bar with the source by
// view judged on the same 72 views at 1024 paths instead of 8192 (the
// tracer's noise is taken out of the statistic).
#include <gtest/gtest.h>

#include "report/converged_targets.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using namespace converged_targets;

TEST(ConvergedTargets, TinyPlanetErrorAtLeastHalved) {
  const Atmosphere atm = fixtures::tiny_planet_atmosphere();
  const ModelErrors e = model_errors(atm, trace_views(atm, 100.0, 4096), true);
  EXPECT_LT(e.mean, 0.5 * e.hillaire) << "Hillaire " << e.hillaire;
  EXPECT_LT(e.relative, 0.5 * e.hillaire) << "Hillaire " << e.hillaire;
}

TEST(ConvergedTargets, RelativeEstimatorBeatsTheMeanUnderForwardDust) {
  const Atmosphere atm = small_mars();
  const ModelErrors e = model_errors(atm, trace_views(atm, 200.0 / kMarsScale, 4096), true);
  EXPECT_LT(e.relative, e.mean) << "Hillaire " << e.hillaire;
  EXPECT_LT(e.relative, e.hillaire) << "mean " << e.mean;
  EXPECT_GT(e.mean, e.hillaire) << "relative " << e.relative;
}

// Mars' bar of the accuracy tier (the source by view within 8 %) at an
// eighth of its paths.
TEST(ConvergedTargets, MarsViewSourceWithinEightPercentAt1024Paths) {
  expect_mars_view_source_within_eight_percent(1024);
}

// Earth's bar of the accuracy tier at an eighth of its paths.
TEST(ConvergedTargets, EarthWithinTwoPercentAt1024Paths) { expect_earth_within_two_percent(1024); }

}  // namespace
}  // namespace skybake

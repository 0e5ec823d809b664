// The report's daytime target at full size: the 72 views of `skybake
// report`, 32768 paths each (daytime_target.hpp says what is measured).
#include <gtest/gtest.h>

#include "report/daytime_target.hpp"

namespace skybake {
namespace {

TEST(DaytimeTarget, BrunetonTableWithinOnePercentOfThePathTracerOnEarth) {
  daytime_target::expect_within_target(daytime_target::table_against_tracer(32768, 8));
}

}  // namespace
}  // namespace skybake

// The report's daytime target cut down for the unit tier: the same table and
// bar (daytime_target.hpp) on the same 72 views at 4096 paths instead of
// 32768, the tracer's noise taken out of the statistic as at full size.
#include <gtest/gtest.h>

#include "report/daytime_target.hpp"

namespace skybake {
namespace {

TEST(DaytimeTarget, BrunetonTableWithinOnePercentAt4096Paths) {
  daytime_target::expect_within_target(daytime_target::table_against_tracer(4096, 8));
}

}  // namespace
}  // namespace skybake

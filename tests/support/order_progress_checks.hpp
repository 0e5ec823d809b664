// The progress of a bake that iterates scattering orders to a tolerance
// (the 4D and 3D tables' tests): what every such bake must report. Header
// only.
#pragma once

#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace skybake::fixtures {

// Checks the fractions `seen` (one thread: in the order reported) of a bake
// whose every order k >= 2 reports `per_order` times and whose end reports
// 1: they never decrease, reach 1 only at the end, and the last order
// starts past half of it (an order weighted 1 / (max_orders + 1) would
// leave the bar near its start and jump to 1). Records the orders used and
// where the last one started as test properties.
inline void expect_progress_follows_the_orders(const std::vector<double>& seen, size_t per_order,
                                               int orders_used) {
  ASSERT_GT(seen.size(), per_order + 2);
  for (size_t i = 1; i < seen.size(); ++i) ASSERT_GE(seen[i], seen[i - 1]) << i;
  for (size_t i = 0; i + 1 < seen.size(); ++i) ASSERT_LT(seen[i], 1.0) << i;
  EXPECT_EQ(seen.back(), 1.0);
  const double last_order_start = seen[seen.size() - 2 - per_order];
  ::testing::Test::RecordProperty("orders_used", orders_used);
  ::testing::Test::RecordProperty("last_order_start", fmt::format("{:.3f}", last_order_start));
  EXPECT_GT(last_order_start, 0.5);
}

}  // namespace skybake::fixtures

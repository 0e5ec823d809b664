// Tests of the progress over scattering orders (atmosphere/order_progress.hpp):
// the fraction never decreases, reaches 1 only when the final stage ends,
// and follows the orders a tolerance will take, not the cap.
#include "atmosphere/order_progress.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// Runs `orders` orders through OrderProgress, residual(k) after order k,
// each order reporting 0, 0.5 and 1 of itself; returns every fraction the
// bake's context received, and in `order_starts` the fraction at the start
// of each order.
std::vector<double> run(int last_order, double tolerance, int final_units, double (*residual)(int),
                        std::vector<double>& order_starts) {
  std::vector<double> seen;
  BakeContext ctx;
  ctx.on_progress = [&](double f) { seen.push_back(f); };
  OrderProgress progress(ctx, last_order, tolerance, final_units);
  for (int k = 1; k <= last_order; ++k) {
    const BakeContext order = progress.order_context(k);
    for (double f : {0.0, 0.5, 1.0}) {
      order.on_progress(f);
      if (f == 0.0) order_starts.push_back(seen.back());
    }
    if (k == 1) continue;
    progress.order_done(k, residual(k));
    if (tolerance > 0.0 && residual(k) < tolerance) break;
  }
  ctx.on_progress(1.0);  // what the bakers report when done
  return seen;
}

void expect_monotone_to_one(const std::vector<double>& seen) {
  for (size_t i = 1; i < seen.size(); ++i) ASSERT_GE(seen[i], seen[i - 1]) << i;
  for (size_t i = 0; i + 1 < seen.size(); ++i) ASSERT_LT(seen[i], 1.0) << i;
  EXPECT_EQ(seen.back(), 1.0);
}

TEST(OrderProgress, FixedOrdersShareTheBakeEqually) {
  std::vector<double> starts;
  const std::vector<double> seen = run(
      4, 0.0, 1, [](int) { return 0.5; }, starts);
  expect_monotone_to_one(seen);
  ASSERT_EQ(starts.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(starts[k], k / 5.0, 1e-12) << k;
}

TEST(OrderProgress, ConvergingOrdersPassHalfBeforeTheLastOrder) {
  // Residuals 0.9^k below a tolerance of 1e-3 take 66 orders of a cap of
  // 1000: weighted by the cap, the bake would end at 7%.
  std::vector<double> starts;
  const std::vector<double> seen = run(
      1000, 1e-3, 1, [](int k) { return std::pow(0.9, k); }, starts);
  expect_monotone_to_one(seen);
  ASSERT_EQ(starts.size(), 66u);
  EXPECT_GT(starts.back(), 0.5);
  EXPECT_GT(starts[starts.size() / 2], 0.25);
}

TEST(OrderProgress, ResidualsThatDoNotDecayFallBackToTheCap) {
  std::vector<double> starts;
  const std::vector<double> seen = run(
      20, 1e-3, 1, [](int) { return 1.0; }, starts);
  expect_monotone_to_one(seen);
  ASSERT_EQ(starts.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_NEAR(starts[k], k / 21.0, 1e-12) << k;
}

TEST(OrderProgress, AnEstimateTooShortNeverReachesOneEarly) {
  // Fast decay at first, then a slow tail: the early estimate is short, and
  // the later orders share what is left without reaching 1.
  std::vector<double> starts;
  const std::vector<double> seen = run(
      200, 1e-4, 0,
      [](int k) { return k < 5 ? std::pow(0.1, k) * 100.0 : 0.1 * std::pow(0.95, k); }, starts);
  expect_monotone_to_one(seen);
  EXPECT_GT(starts.size(), 100u);
}

}  // namespace
}  // namespace skybake

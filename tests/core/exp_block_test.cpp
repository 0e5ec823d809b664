// Tests of exp_block and expm1_block (core/kernels/exp_block.hpp) against
// std::exp and std::expm1, on the best SIMD target this CPU runs
// (tests/core/kernels_test.cpp holds every target to the one-value
// functions).
#include "core/kernels/exp_block.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// Over the whole range the precondition allows, and at the points where
// the reduction changes k (odd multiples of ln 2 / 2) and at 0: within
// 4e-16 relative (libm's exp is itself within 1 ulp, 2.2e-16).
TEST(ExpBlock, MatchesStdExpOverItsRange) {
  std::vector<double> x;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> wide(-708.0, 708.0), narrow(-90.0, 1.0);
  for (int i = 0; i < 100000; ++i) x.push_back(i % 2 ? wide(rng) : narrow(rng));
  for (int k = -1020; k <= 1020; ++k) {
    const double edge = (k + 0.5) * std::log(2.0);
    if (std::abs(edge) <= 708.0)
      for (double d : {-1e-12, 0.0, 1e-12}) x.push_back(edge + d);
  }
  for (double v : {0.0, -0.0, 1e-300, -1e-300, 708.0, -708.0, 1.0, -1.0}) x.push_back(v);
  std::vector<double> y = x;
  exp_block(y.data(), y.size());
  for (size_t i = 0; i < x.size(); ++i)
    ASSERT_NEAR(y[i] / std::exp(x[i]), 1.0, 4e-16) << "x = " << x[i];
}

TEST(ExpBlock, OddLengthsAndEmpty) {
  // The elements past the last whole vector are computed too.
  for (size_t n : {size_t(0), size_t(1), size_t(3), size_t(17)}) {
    std::vector<double> x(n), y;
    for (size_t i = 0; i < n; ++i) x[i] = -0.37 * double(i);
    y = x;
    exp_block(y.data(), n);
    for (size_t i = 0; i < n; ++i) EXPECT_NEAR(y[i] / std::exp(x[i]), 1.0, 4e-16) << n << " " << i;
  }
}

// expm1_block against std::expm1: relative error at tiny x (where
// exp(x) - 1 would lose every digit), at the reduction's edges and over
// the range the precondition allows.
TEST(Expm1Block, MatchesStdExpm1OverItsRange) {
  std::vector<double> x;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> wide(-708.0, 708.0), narrow(-3.0, 3.0);
  std::uniform_real_distribution<double> exponent(-300.0, -1.0);
  for (int i = 0; i < 100000; ++i) {
    x.push_back(i % 3 == 0 ? wide(rng) : narrow(rng));
    const double tiny = std::pow(10.0, exponent(rng));
    x.push_back(i % 2 ? tiny : -tiny);
  }
  for (int k = -1020; k <= 1020; ++k) {
    const double edge = (k + 0.5) * std::log(2.0);
    if (std::abs(edge) <= 708.0)
      for (double d : {-1e-12, 0.0, 1e-12}) x.push_back(edge + d);
  }
  for (double v : {0.0, 1e-300, -1e-300, 708.0, -708.0, 1.0, -1.0}) x.push_back(v);
  std::vector<double> y = x;
  expm1_block(y.data(), y.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double want = std::expm1(x[i]);
    if (want == 0.0)
      ASSERT_EQ(y[i], 0.0) << "x = " << x[i];
    else
      ASSERT_NEAR(y[i] / want, 1.0, 1e-15) << "x = " << x[i];
  }
}

}  // namespace
}  // namespace skybake

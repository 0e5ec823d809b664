// Tests of reference/adaptive_quadrature.hpp against closed-form integrals:
// the rules' degrees of exactness, convergence to 1e-12 on smooth and stiff
// integrands, breakpoints, per-channel tolerances, and honest failure.
#include "reference/adaptive_quadrature.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace skybake {
namespace {

TEST(AdaptiveQuadrature, RuleWeightsIntegrateConstants) {
  using namespace quadrature_detail;
  double kronrod = kKronrodWeights[7], gauss = kGaussWeights[3];
  for (int j = 0; j < 7; ++j) kronrod += 2.0 * kKronrodWeights[j];
  for (int j = 0; j < 3; ++j) gauss += 2.0 * kGaussWeights[j];
  EXPECT_NEAR(kronrod, 2.0, 1e-15);
  EXPECT_NEAR(gauss, 2.0, 1e-15);
}

// Both rules integrate x^k exactly up to degree 13 (G7), so the error
// estimate vanishes and one interval (15 evaluations) is enough.
TEST(AdaptiveQuadrature, PolynomialsUpToDegree13InOneInterval) {
  for (int k = 0; k <= 13; ++k) {
    const double a = -0.5, b = 2.0;
    const double exact = (std::pow(b, k + 1) - std::pow(a, k + 1)) / (k + 1);
    const auto r = integrate_adaptive([k](double x) { return std::pow(x, k); }, a, b);
    EXPECT_TRUE(r.converged) << k;
    EXPECT_EQ(r.evaluations, 15) << k;
    EXPECT_NEAR(r.value, exact, 1e-14 * std::abs(exact)) << k;
  }
}

// K15 alone is exact to degree 22 (3n + 1 for n = 7).
TEST(AdaptiveQuadrature, KronrodExactToDegree22) {
  QuadratureOptions one_interval;
  one_interval.max_evaluations = 15;
  for (int k = 14; k <= 22; ++k) {
    const auto r =
        integrate_adaptive([k](double x) { return std::pow(x, k); }, 0.0, 1.0, one_interval);
    EXPECT_EQ(r.evaluations, 15);
    EXPECT_FALSE(r.converged);  // G7 is not exact, so the estimate is not 0
    EXPECT_NEAR(r.value, 1.0 / (k + 1), 1e-15) << k;
    EXPECT_GE(r.error, std::abs(r.value - 1.0 / (k + 1)));
  }
}

struct ExpCase {
  double rate, a, b;
};

// Exponentials, mild and stiff, to 1e-12 relative; the estimate bounds the
// actual error.
TEST(AdaptiveQuadrature, ExponentialsTo1em12) {
  QuadratureOptions o;
  o.relative_tolerance = 1e-12;
  for (const ExpCase c :
       {ExpCase{-1.0, 0.0, 10.0}, ExpCase{3.0, -3.0, 2.0}, ExpCase{-100.0, 0.0, 100.0},
        ExpCase{-1.0 / 8000.0, 0.0, 1e5}, ExpCase{-1e4, 0.0, 1.0}}) {
    const double exact = (std::exp(c.rate * c.b) - std::exp(c.rate * c.a)) / c.rate;
    const auto r = integrate_adaptive([&](double x) { return std::exp(c.rate * x); }, c.a, c.b, o);
    EXPECT_TRUE(r.converged) << c.rate;
    EXPECT_NEAR(r.value, exact, 1e-12 * std::abs(exact)) << c.rate;
    EXPECT_GE(r.error, std::abs(r.value - exact)) << c.rate;
  }
}

TEST(AdaptiveQuadrature, BreakpointAtAKinkIsExact) {
  const auto f = [](double x) { return std::abs(x - 1.0 / 3.0); };
  const double exact = 5.0 / 18.0;  // (1/3)^2 / 2 + (2/3)^2 / 2
  const auto with = integrate_adaptive(f, 0.0, 1.0, {}, {1.0 / 3.0});
  EXPECT_TRUE(with.converged);
  EXPECT_EQ(with.evaluations, 30);
  EXPECT_NEAR(with.value, exact, 1e-15);
  // Without it the kink costs subdivisions but the tolerance is still met.
  const auto without = integrate_adaptive(f, 0.0, 1.0);
  EXPECT_TRUE(without.converged);
  EXPECT_GT(without.evaluations, 30);
  EXPECT_NEAR(without.value, exact, 1e-10 * exact);
}

TEST(AdaptiveQuadrature, BreakpointAtAJumpIsExact) {
  const auto step = [](double x) { return x < 0.3 ? 1.0 : 2.0; };
  const auto r =
      integrate_adaptive(step, 0.0, 1.0, {}, {0.3, -5.0, 7.0, 0.3});  // outside ones ignored
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.evaluations, 30);
  EXPECT_NEAR(r.value, 1.7, 1e-15);
}

// Each channel meets the relative tolerance on its own scale.
TEST(AdaptiveQuadrature, RgbChannelsMeetTheirOwnTolerance) {
  QuadratureOptions o;
  o.relative_tolerance = 1e-11;
  const auto f = [](double x) {
    return glm::dvec3(std::exp(-x), 1e-20 * std::exp(-x), std::exp(-50.0 * x));
  };
  const auto r = integrate_adaptive(f, 0.0, 1.0, o);
  const double e1 = 1.0 - std::exp(-1.0), e50 = (1.0 - std::exp(-50.0)) / 50.0;
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.value.x, e1, 1e-11 * e1);
  EXPECT_NEAR(r.value.y, 1e-20 * e1, 1e-31 * e1);
  EXPECT_NEAR(r.value.z, e50, 1e-11 * e50);
}

TEST(AdaptiveQuadrature, ReversedAndEmptyIntervals) {
  const auto f = [](double x) { return x * x; };
  EXPECT_NEAR(integrate_adaptive(f, 1.0, 0.0).value, -1.0 / 3.0, 1e-16);
  const auto empty = integrate_adaptive(f, 2.0, 2.0);
  EXPECT_EQ(empty.value, 0.0);
  EXPECT_EQ(empty.evaluations, 0);
  EXPECT_TRUE(empty.converged);
}

TEST(AdaptiveQuadrature, IntegrableEndpointSingularity) {
  QuadratureOptions o;
  o.relative_tolerance = 1e-9;
  const auto r = integrate_adaptive([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0, o);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.value, 2.0, 2e-9);
}

// A divergent integral exhausts the budget and says so.
TEST(AdaptiveQuadrature, ReportsFailureWithinBudget) {
  QuadratureOptions o;
  o.max_evaluations = 3000;
  const auto r = integrate_adaptive([](double x) { return 1.0 / x; }, 0.0, 1.0, o);
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.evaluations, 3000);
  EXPECT_TRUE(std::isfinite(r.value));
}

}  // namespace
}  // namespace skybake

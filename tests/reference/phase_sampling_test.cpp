// Tests of reference/phase_sampling.hpp and reference/counter_rng.hpp:
// each sampler's CDF and inverse round-trip, its density is the CDF's
// derivative and 2 pi times phase.hpp's phase, and sampled moments match
// the density's moments (by quadrature) within 5 standard errors.
#include "reference/phase_sampling.hpp"

#include <cmath>
#include <functional>
#include <set>

#include <gtest/gtest.h>

#include "atmosphere/phase.hpp"
#include "reference/adaptive_quadrature.hpp"
#include "reference/counter_rng.hpp"

namespace skybake {
namespace {

const double kGs[] = {-0.9, -0.3, 0.0, 1e-8, 0.5, 0.8, 0.999};

TEST(PhaseSampling, RayleighInverseCdfRoundTrips) {
  EXPECT_NEAR(rayleigh_cosine_from_cdf(0.0), -1.0, 1e-15);
  EXPECT_NEAR(rayleigh_cosine_from_cdf(0.5), 0.0, 1e-15);
  EXPECT_NEAR(rayleigh_cosine_from_cdf(1.0), 1.0, 1e-15);
  for (int i = 0; i <= 1000; ++i) {
    const double u = i / 1000.0;
    EXPECT_NEAR(rayleigh_cosine_cdf(rayleigh_cosine_from_cdf(u)), u, 1e-14) << u;
  }
}

TEST(PhaseSampling, HenyeyGreensteinInverseCdfRoundTrips) {
  for (double g : kGs) {
    EXPECT_NEAR(henyey_greenstein_cosine_cdf(-1.0, g), 0.0, 1e-15) << g;
    EXPECT_NEAR(henyey_greenstein_cosine_cdf(1.0, g), 1.0, 1e-15) << g;
    for (int i = 0; i <= 1000; ++i) {
      // c carries a rounding error of a few ulp (2e-15 at most), which moves
      // the CDF by the density times that: for g = 0.999 the density
      // reaches 1e6 near c = 1.
      const double u = i / 1000.0, c = henyey_greenstein_cosine_from_cdf(u, g);
      const double slack = 1e-14 + 2e-15 * henyey_greenstein_cosine_pdf(c, g);
      EXPECT_NEAR(henyey_greenstein_cosine_cdf(c, g), u, slack) << g << " " << u;
    }
  }
}

// The densities are the CDFs' derivatives and 2 pi times the phase functions.
TEST(PhaseSampling, DensitiesMatchCdfsAndPhaseFunctions) {
  const double h = 1e-6;
  for (int i = 1; i < 100; ++i) {
    const double c = -1.0 + 2.0 * i / 100.0;
    const double d_rayleigh = (rayleigh_cosine_cdf(c + h) - rayleigh_cosine_cdf(c - h)) / (2 * h);
    EXPECT_NEAR(d_rayleigh, rayleigh_cosine_pdf(c), 1e-7);
    EXPECT_NEAR(rayleigh_cosine_pdf(c), 2 * kPi * rayleigh_phase(c), 1e-14);
    for (double g : {-0.9, 0.0, 0.5, 0.8}) {
      const double pdf = henyey_greenstein_cosine_pdf(c, g);
      const double d_hg =
          (henyey_greenstein_cosine_cdf(c + h, g) - henyey_greenstein_cosine_cdf(c - h, g)) /
          (2 * h);
      EXPECT_NEAR(d_hg, pdf, 1e-6 * std::max(1.0, pdf)) << g << " " << c;
      EXPECT_NEAR(pdf, 2 * kPi * henyey_greenstein_phase(c, g), 1e-13 * pdf);
      const double cs = cornette_shanks_cosine_pdf(c, g);
      EXPECT_NEAR(cs, 2 * kPi * cornette_shanks_phase(c, g), 1e-13 * cs);
    }
  }
}

// Mean of f(c) under a density on [-1, 1], by adaptive quadrature.
double density_moment(const std::function<double(double)>& pdf,
                      const std::function<double(double)>& f) {
  QuadratureOptions o;
  o.relative_tolerance = 1e-12;
  o.absolute_tolerance = 1e-14;
  return integrate_adaptive([&](double c) { return pdf(c) * f(c); }, -1.0, 1.0, o).value;
}

// Sampled mean of c and c^2 against the density's, within 5 standard errors.
void expect_moments(PhaseKind kind, double g, const std::function<double(double)>& pdf) {
  ASSERT_NEAR(density_moment(pdf, [](double) { return 1.0; }), 1.0, 1e-10);
  CounterRng rng(7, uint64_t(kind), uint64_t(std::llround(g * 1e6) + 10000000));
  const int n = 200000;
  for (int power : {1, 2}) {
    const auto f = [power](double c) { return power == 1 ? c : c * c; };
    double sum = 0.0, sum_sq = 0.0;
    CounterRng local = rng;
    for (int i = 0; i < n; ++i) {
      const double c = sample_phase_cosine(kind, g, local);
      ASSERT_GE(c, -1.0);
      ASSERT_LE(c, 1.0);
      sum += f(c);
      sum_sq += f(c) * f(c);
    }
    const double mean = sum / n, sigma = std::sqrt((sum_sq / n - mean * mean) / n);
    EXPECT_NEAR(mean, density_moment(pdf, f), 5.0 * sigma + 1e-12)
        << int(kind) << " g " << g << " power " << power;
  }
}

TEST(PhaseSampling, SampledMomentsMatchDensities) {
  expect_moments(PhaseKind::rayleigh, 0.0, rayleigh_cosine_pdf);
  for (double g : {-0.9, 0.0, 0.8, 0.999}) {
    expect_moments(PhaseKind::henyey_greenstein, g,
                   [g](double c) { return henyey_greenstein_cosine_pdf(c, g); });
    expect_moments(PhaseKind::cornette_shanks, g,
                   [g](double c) { return cornette_shanks_cosine_pdf(c, g); });
  }
}

// Closed forms: Rayleigh's E[c^2] = 2/5, HG's E[c] = g (forward for g > 0).
TEST(PhaseSampling, ClosedFormMoments) {
  EXPECT_NEAR(density_moment(rayleigh_cosine_pdf, [](double c) { return c * c; }), 0.4, 1e-12);
  for (double g : {-0.5, 0.3, 0.8})
    EXPECT_NEAR(density_moment([g](double c) { return henyey_greenstein_cosine_pdf(c, g); },
                               [](double c) { return c; }),
                g, 1e-10);
}

TEST(PhaseSampling, DirectionFromCosine) {
  CounterRng rng(3, 0, 0);
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 axis(2 * rng() - 1, 2 * rng() - 1, 2 * rng() - 1);
    if (i == 0) axis = {0, 0, 1};
    if (i == 1) axis = {0, 0, -1};
    if (i == 2) axis = {1, 0, 0};
    axis = glm::normalize(axis);
    const double c = 2 * rng() - 1;
    const glm::dvec3 w = direction_from_cosine(axis, c, rng());
    EXPECT_NEAR(glm::length(w), 1.0, 1e-14);
    EXPECT_NEAR(glm::dot(w, axis), c, 1e-12);
  }
  // Uniform azimuths average to the axis component.
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.4, 0.5));
  glm::dvec3 mean(0.0);
  for (int k = 0; k < 360; ++k) mean += direction_from_cosine(axis, 0.25, (k + 0.5) / 360.0);
  mean /= 360.0;
  EXPECT_NEAR(glm::length(mean - 0.25 * axis), 0.0, 1e-12);
}

// Cosine-weighted hemisphere: E[cos] = 2/3, never below the horizon.
TEST(PhaseSampling, CosineHemisphere) {
  CounterRng rng(5, 1, 2);
  const glm::dvec3 n = glm::normalize(glm::dvec3(-1.0, 2.0, 0.5));
  const int count = 100000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < count; ++i) {
    const double c = glm::dot(sample_cosine_hemisphere(n, rng), n);
    ASSERT_GE(c, -1e-15);
    sum += c;
    sum_sq += c * c;
  }
  const double mean = sum / count, sigma = std::sqrt((sum_sq / count - mean * mean) / count);
  EXPECT_NEAR(mean, 2.0 / 3.0, 5 * sigma);
}

TEST(CounterRng, DeterministicUniformAndDistinctStreams) {
  CounterRng a(1, 2, 3), b(1, 2, 3);
  std::set<uint64_t> firsts;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
  for (uint64_t s = 0; s < 1000; ++s) firsts.insert(CounterRng(1, s, 0).next_u64());
  for (uint64_t c = 1; c < 1000; ++c) firsts.insert(CounterRng(1, 0, c).next_u64());
  EXPECT_EQ(firsts.size(), 1999u);
  CounterRng u(9, 9, 9);
  const int n = 100000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = u.uniform();
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
    sum += x;
  }
  EXPECT_NEAR(sum / n, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
}

}  // namespace
}  // namespace skybake

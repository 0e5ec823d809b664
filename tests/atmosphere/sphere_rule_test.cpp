// Tests of the direction rules of the multiple-scattering integral
// (atmosphere/sphere_rule.hpp, multiscattering_rule): Gauss-Legendre against
// monomials, the symmetric product rule against closed forms over the sphere
// (a constant, polynomials in the zenith cosine, a kink at the split,
// functions symmetric about the x-z plane), a conservative uniform slab
// whose f_ms is a one-dimensional integral of chord lengths, and a 32 x 32
// Earth table with the terminator mapping against many directions, and a
// 32 x 32 tiny planet table whose quadratic altitude axis brings it within
// 10 %.
#include "atmosphere/sphere_rule.hpp"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error_stats.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "verify/query_points.hpp"

namespace skybake {
namespace {

TEST(GaussLegendre, IntegratesMonomialsBelowDegreeTwoN) {
  for (int n : {1, 2, 3, 6, 13, 26}) {
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    for (int k = 0; k < 2 * n; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += w[size_t(i)] * std::pow(x[size_t(i)], k);
      const double exact = k % 2 == 1 ? 0.0 : 2.0 / (k + 1);
      EXPECT_NEAR(sum, exact, 1e-13) << n << " " << k;
    }
    for (int i = 1; i < n; ++i) EXPECT_LT(x[size_t(i - 1)], x[size_t(i)]);
  }
}

// Mean of f over the sphere with the rule (the integral over 4 pi divided by 4 pi).
template <class F>
double rule_mean(const SphereRule& rule, F f) {
  double sum = 0.0;
  for (size_t k = 0; k < rule.dirs.size(); ++k) sum += rule.weights[k] * f(rule.dirs[k]);
  return sum;
}

TEST(SymmetricGaussRule, ClosedFormsOverTheSphere) {
  const double split = -0.3;
  const SphereRule rule = symmetric_gauss_rule(3, 5, 4, split);
  ASSERT_EQ(rule.dirs.size(), size_t((3 + 5) * 4));
  for (const glm::dvec3& d : rule.dirs) {
    EXPECT_NEAR(glm::length(d), 1.0, 1e-14);
    EXPECT_GT(d.y, 0.0);  // the half circle on one side of the x-z plane
  }
  // A constant: 4 pi, i.e. a mean of 1.
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3) { return 1.0; }), 1.0, 1e-14);
  // Polynomials in the zenith cosine: mean z^2 = 1/3, z^4 = 1/5, z = 0.
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.z; }), 0.0, 1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.z * d.z; }), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return std::pow(d.z, 4); }), 0.2, 1e-14);
  // A kink at the split is integrated exactly: mean of max(z - s, 0) is (1 - s)^2 / 4.
  EXPECT_NEAR(rule_mean(rule, [&](glm::dvec3 d) { return std::max(d.z - split, 0.0); }),
              (1.0 - split) * (1.0 - split) / 4.0, 1e-14);
  // Symmetric about the x-z plane: mean x^2 = y^2 = 1/3 (each node stands
  // for its mirror too), x = 0, (1 + x)^2 = 4/3, x^2 z^2 = 1/15.
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.x * d.x; }), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.y * d.y; }), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.x; }), 0.0, 1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return (1 + d.x) * (1 + d.x); }), 4.0 / 3.0,
              1e-14);
  EXPECT_NEAR(rule_mean(rule, [](glm::dvec3 d) { return d.x * d.x * d.z * d.z; }), 1.0 / 15.0,
              1e-14);
  // Not exact past its degree: 2 azimuths (4 on the circle) miss x^4's 1/5.
  const SphereRule coarse = symmetric_gauss_rule(3, 5, 2, split);
  EXPECT_GT(std::abs(rule_mean(coarse, [](glm::dvec3 d) { return std::pow(d.x, 4); }) - 0.2),
            1e-3);
}

TEST(SymmetricGaussRule, ShapeSpendsAtMostTheBudgetMostlyAboveTheSplit) {
  for (int rays : {4, 16, 64, 96, 128, 256, 2048}) {
    const SymmetricGaussShape s = symmetric_gauss_shape(rays);
    EXPECT_LE((s.below + s.above) * s.azimuths, rays) << rays;
    EXPECT_GE((s.below + s.above) * s.azimuths, rays / 2) << rays;
    EXPECT_GT(s.above, s.below) << rays;
  }
}

// Distance from radius r along zenith cosine mu to the ground or the top.
double chord(const Atmosphere& atm, double r, double mu) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double ground = r * r * (mu * mu - 1.0) + rb * rb;
  if (mu < 0.0 && ground >= 0.0) return -r * mu - std::sqrt(ground);
  return -r * mu + std::sqrt(r * r * (mu * mu - 1.0) + rt * rt);
}

// Conservative (no absorption) uniform slab: per direction L_f = 1 - T(end)
// exactly (the energy-conserving segments telescope), so f_ms is the mean
// over the sphere of 1 - exp(-sigma d(mu)), a 1D integral over mu, here by a
// fine midpoint rule on each side of the horizon. On the ground the split
// is the only edge and the rule is exact to rounding (measured 3e-12); above
// it, the chord to the ground has a square-root edge at the horizon, which
// 6 Gauss nodes below it resolve to ~1.3e-3 (Fibonacci 128: 4e-3 at 1 km).
TEST(SymmetricGaussRule, ConservativeSlabTransferMatchesTheChordIntegral) {
  const double sigma = 2e-6;
  const Atmosphere atm = fixtures::uniform_slab_atmosphere(glm::dvec3(sigma), glm::dvec3(0.0));
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  for (double h : {0.0, 1e3, 20e3}) {
    const double r = atm.bottom_radius_m + h;
    const double ratio = atm.bottom_radius_m / r;
    const double mu_h = -std::sqrt(1.0 - ratio * ratio);
    double exact = 0.0;
    const int n = 200000;
    for (auto [lo, hi] : {std::pair{-1.0, mu_h}, std::pair{mu_h, 1.0}})
      for (int i = 0; i < n; ++i) {
        const double mu = lo + (i + 0.5) * (hi - lo) / n;
        exact += 0.5 * (hi - lo) / n * (1.0 - std::exp(-sigma * chord(atm, r, mu)));
      }
    const auto f_ms = [&](DirectionQuadrature q, int rays) {
      return compute_multiscattering(atm, t, r, 0.5, multiscattering_rule(q, rays, atm, r), 4)
          .f_ms.x;
    };
    const double gauss = f_ms(DirectionQuadrature::symmetric_gauss, 128);
    const double fib = f_ms(DirectionQuadrature::fibonacci, 128);
    EXPECT_NEAR(gauss, exact, 2e-3 * exact) << h << " fibonacci: " << fib;
  }
}

// The table's own error with the terminator mapping: 128 rays of the
// symmetric rule bring a 32 x 32 Earth table within 10 % everywhere against
// the integral with 2048 rays at the query points themselves (the same
// steps, so the direction rule and the interpolation are what is measured);
// the same table with 128 Fibonacci directions is off by far more.
TEST(SymmetricGaussRule, EarthTerminatorTableWithinTenPercent) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {128, 64, 40}, {});
  const int steps = 20;
  std::vector<RadiusCosine> points;
  std::vector<glm::dvec3> reference;
  for (size_t i = 0; i < 96; ++i) {
    const RadiusCosine p = multiscattering_query(atm, i);
    const double ratio = atm.bottom_radius_m / p.r;
    points.push_back(p);
    reference.push_back(compute_multiscattering(
                            atm, t, p.r, p.mu,
                            symmetric_gauss_rule(32, 32, 32, -std::sqrt(1.0 - ratio * ratio)),
                            steps)
                            .psi_ms);
  }
  double max_rel[2] = {0.0, 0.0};
  for (DirectionQuadrature q : {DirectionQuadrature::fibonacci, DirectionQuadrature::symmetric_gauss}) {
    MultiscatteringLutSpec spec;
    spec.directions = 128;
    spec.steps = steps;
    spec.sun_mapping = SunMapping::terminator;
    spec.quadrature = q;
    const Texture ms = bake_multiscattering_lut(atm, t, spec, {});
    ErrorTally tally;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 v = lookup_multiscattering(ms, atm, points[i].r, points[i].mu);
      for (int c = 0; c < 3; ++c) tally.add(v[c], reference[i][c]);
    }
    max_rel[q == DirectionQuadrature::symmetric_gauss] = tally.stats().max_rel;
  }
  EXPECT_LE(max_rel[1], 0.10) << "fibonacci: " << max_rel[0];
  EXPECT_GT(max_rel[0], 2.0 * max_rel[1]);
}

// The largest relative error of a table's lookups at the report's first
// `count` query points against the integral there with 1024 rays of the
// symmetric rule and the same steps: with the table's texels from 512 rays,
// what is left is the interpolation between texels.
double interpolation_max_rel(const Atmosphere& atm, const Texture& transmittance,
                             const MultiscatteringLutSpec& spec, size_t count) {
  const Texture ms = bake_multiscattering_lut(atm, transmittance, spec, {});
  ErrorTally tally;
  for (size_t i = 0; i < count; ++i) {
    const RadiusCosine p = multiscattering_query(atm, i);
    const glm::dvec3 reference =
        compute_multiscattering(
            atm, transmittance, p.r, p.mu,
            multiscattering_rule(DirectionQuadrature::symmetric_gauss, 1024, atm, p.r), spec.steps)
            .psi_ms;
    const glm::dvec3 v = lookup_multiscattering(ms, atm, p.r, p.mu);
    for (int c = 0; c < 3; ++c) tally.add(v[c], reference[c]);
  }
  return tally.stats().max_rel;
}

// The tiny planet's Psi_ms for a sun below the horizon falls steeply in the
// first few hundred metres: with rows evenly spaced (the next one ~1 km up)
// a 32 x 32 table misses 10 % at the report's 128 points; rows at
// h = H x^2 meet it (docs/decisions/multiscattering-table-axes.md).
TEST(SymmetricGaussRule, TinyPlanetQuadraticAltitudeTableWithinTenPercent) {
  const Atmosphere atm = fixtures::tiny_planet_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {128, 64, 40}, {});
  MultiscatteringLutSpec spec;
  spec.directions = 512;
  spec.steps = 40;
  spec.sun_mapping = SunMapping::terminator;
  spec.quadrature = DirectionQuadrature::symmetric_gauss;
  const double linear = interpolation_max_rel(atm, t, spec, 128);
  spec.altitude_mapping = AltitudeMapping::quadratic;
  const double quadratic = interpolation_max_rel(atm, t, spec, 128);
  std::printf("[ measured ] tiny planet 32x32 max_rel: linear altitude %.4f, quadratic %.4f\n",
              linear, quadratic);
  EXPECT_LE(quadratic, 0.10);
  EXPECT_GT(linear, 0.10);
}

}  // namespace
}  // namespace skybake

// Tests of the view-dependent source's axes and fit
// (atmosphere/psi_view_nodes.hpp): each axis mapping against its inverse,
// its ends and where it crowds its nodes; the fit against sources it can
// hold exactly (a constant, a sum of the two terms) and against a closed-form
// lobe it must follow as well as its span allows (Henyey-Greenstein,
// g = 0.85, in nu).
#include "atmosphere/psi_view_nodes.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/phase.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

TEST(PsiViewNodes, AxesRoundTripAndEnds) {
  for (int i = 0; i <= 100; ++i) {
    const double x = i / 100.0;
    // (the quarter power takes 1e-16 in nu to 1e-4 in x near the sun: the
    // round trip through the cosine is exact to ~1e-16^(1/4) x^-3 there)
    EXPECT_NEAR(nu_node_unit_from_cosine(nu_node_cosine_from_unit(x)), x, 1e-9) << x;
    EXPECT_NEAR(zenith_node_unit_from_cosine(zenith_node_cosine_from_unit(x)), x, 1e-12) << x;
  }
  EXPECT_EQ(nu_node_unit_from_cosine(1.0), 0.0);  // the sun at the first node
  EXPECT_EQ(nu_node_unit_from_cosine(-1.0), 1.0);
  EXPECT_EQ(zenith_node_unit_from_cosine(-1.0), 0.0);
  EXPECT_EQ(zenith_node_unit_from_cosine(0.0), 0.5);  // the horizontal in the middle
  EXPECT_EQ(zenith_node_unit_from_cosine(1.0), 1.0);
  EXPECT_EQ(nu_node_unit_from_cosine(1.5), 0.0);  // clamped
  // 8 nodes: the second one 2.3 degrees off the sun, the third 9.4.
  EXPECT_NEAR(std::acos(nu_node_cosine_from_unit(1.0 / 7.0)) / kDeg, 2.34, 0.01);
  EXPECT_NEAR(std::acos(nu_node_cosine_from_unit(2.0 / 7.0)) / kDeg, 9.37, 0.01);
}

TEST(PsiViewNodes, NodePairsCoverTheAxis) {
  EXPECT_EQ(node_pair(8, 0.0).first, 0);
  EXPECT_EQ(node_pair(8, 0.0).f, 0.0);
  EXPECT_EQ(node_pair(8, 1.0).first, 6);  // the last pair, weight 1 on the last node
  EXPECT_EQ(node_pair(8, 1.0).f, 1.0);
  const NodePair p = node_pair(5, 0.6);  // s = 2.4
  EXPECT_EQ(p.first, 2);
  EXPECT_NEAR(p.f, 0.4, 1e-12);
}

// Directions of a Fibonacci set: cosines to a sun 40 degrees up and zenith cosines.
struct FitDirections {
  std::vector<double> nu, mu_v;
  std::vector<glm::dvec3> w;
};
FitDirections fit_directions(int n) {
  FitDirections d;
  const glm::dvec3 sun(std::cos(40.0 * kDeg), 0.0, std::sin(40.0 * kDeg));
  for (const glm::dvec3& v : fibonacci_sphere_directions(n)) {
    d.nu.push_back(glm::dot(v, sun));
    d.mu_v.push_back(v.z);
    d.w.push_back(glm::dvec3(1.0));
  }
  return d;
}

TEST(PsiViewNodes, AConstantSourceIsHeldByTheNuTermAlone) {
  const FitDirections d = fit_directions(1024);
  const glm::dvec3 psi(0.02, 0.05, 0.3);
  const PsiViewShape shape{8, 8};
  const std::vector<glm::dvec3> nodes =
      fit_view_nodes(d.nu, d.mu_v, std::vector<glm::dvec3>(d.nu.size(), psi), d.w, psi, shape);
  ASSERT_EQ(nodes.size(), 16u);
  for (int k = 0; k < 8; ++k)
    for (int c = 0; c < 3; ++c) {
      // (the split of the constant is the weak ridge's: conditioned to ~1e-8)
      EXPECT_NEAR(nodes[k][c], psi[c], 1e-6 * psi[c]) << k;
      EXPECT_NEAR(nodes[8 + k][c], 0.0, 1e-6 * psi[c]) << k;
    }
}

TEST(PsiViewNodes, ASumOfTheTwoTermsIsReproducedEverywhere) {
  const FitDirections d = fit_directions(2048);
  const PsiViewShape shape{6, 5};
  // Node values of a truth the form holds exactly.
  std::vector<glm::dvec3> truth;
  for (int k = 0; k < 6; ++k) truth.push_back(glm::dvec3(1.0 + 3.0 * std::exp(-k), 2.0, 0.5 + k));
  for (int m = 0; m < 5; ++m) truth.push_back(glm::dvec3(0.3 * m, 1.0 - 0.2 * m, 0.1 * m * m));
  std::vector<glm::dvec3> j;
  for (size_t v = 0; v < d.nu.size(); ++v)
    j.push_back(evaluate_view_nodes(truth, shape, d.nu[v], d.mu_v[v]));
  const std::vector<glm::dvec3> fit = fit_view_nodes(d.nu, d.mu_v, j, d.w, glm::dvec3(1.0), shape);
  // The split of a constant between the terms is the ridge's choice and
  // the curvature penalty (1e-3 of the weights) bends it a little where the
  // truth is not straight; the sum is the data's.
  for (size_t v = 0; v < d.nu.size(); v += 7) {
    const glm::dvec3 got = evaluate_view_nodes(fit, shape, d.nu[v], d.mu_v[v]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], j[v][c], 1e-2 * j[v][c]) << v;
  }
}

TEST(PsiViewNodes, FollowsAForwardLobeInNu) {
  // j = Henyey-Greenstein of g = 0.85 in nu, a closed form. Least squares
  // is the best of its span: no worse over the directions than the lobe
  // interpolated between its values at the nodes (also in the span), and it
  // keeps the power (the constant is in the span).
  const FitDirections d = fit_directions(20000);
  const double g = 0.85;
  std::vector<glm::dvec3> j;
  for (double nu : d.nu) j.push_back(glm::dvec3(henyey_greenstein_phase(nu, g)));
  const PsiViewShape shape{12, 0};
  const std::vector<glm::dvec3> fit =
      fit_view_nodes(d.nu, d.mu_v, j, d.w, glm::dvec3(1.0 / (4.0 * kPi)), shape);
  std::vector<glm::dvec3> interpolant;
  for (int k = 0; k < 12; ++k)
    interpolant.push_back(glm::dvec3(henyey_greenstein_phase(nu_node_cosine_from_unit(k / 11.0), g)));
  double fit_sq = 0.0, interpolant_sq = 0.0, sum_fit = 0.0, sum_j = 0.0;
  for (size_t v = 0; v < d.nu.size(); ++v) {
    const double f = evaluate_view_nodes(fit, shape, d.nu[v], 0.0).x;
    const double i = evaluate_view_nodes(interpolant, shape, d.nu[v], 0.0).x;
    fit_sq += (f - j[v].x) * (f - j[v].x);
    interpolant_sq += (i - j[v].x) * (i - j[v].x);
    sum_fit += f;
    sum_j += j[v].x;
  }
  EXPECT_LE(fit_sq, interpolant_sq);
  EXPECT_GT(interpolant_sq, 0.0);
  EXPECT_NEAR(sum_fit / sum_j, 1.0, 1e-3);
  // The lobe's mean is 1 / (4 pi), its peak 150 times that: the fit's RMS
  // error, mostly inside the first node's spacing, is a fraction of the mean.
  EXPECT_LT(std::sqrt(fit_sq / double(d.nu.size())), 0.25 / (4.0 * kPi));
}

TEST(PsiViewNodes, RefusesShapesItCannotFit) {
  const FitDirections d = fit_directions(64);
  const std::vector<glm::dvec3> j(d.nu.size(), glm::dvec3(1.0));
  EXPECT_THROW(fit_view_nodes(d.nu, d.mu_v, j, d.w, glm::dvec3(1.0), {1, 0}), Error);
  EXPECT_THROW(fit_view_nodes(d.nu, d.mu_v, j, d.w, glm::dvec3(1.0), {4, 1}), Error);
}

}  // namespace
}  // namespace skybake

// Curl noise (src/noise/curl.hpp): divergence ~ 0 by central differences,
// against a gradient field of the same potential as a control that the
// measure does see divergence; tiling; orthogonality in 2D.
#include "noise/curl.hpp"

#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace skybake {
namespace {

float dyadic(std::mt19937& rng, float lo, float hi) {
  std::uniform_int_distribution<int> d(int(lo * 1024), int(hi * 1024));
  return float(d(rng)) / 1024.0f;
}

// Mean |divergence| / mean |Jacobian| (Frobenius) of a 3D field by central
// differences at random points. Small for a solenoidal field, O(1) otherwise.
double divergence_ratio3(const std::function<glm::vec3(glm::vec3)>& v, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  const float h = 1e-3f;
  double div_sum = 0, jac_sum = 0;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    double div = 0, jac2 = 0;
    for (int a = 0; a < 3; ++a) {
      glm::vec3 e(0.0f);
      e[a] = h;
      const glm::vec3 d = (v(p + e) - v(p - e)) / (2 * h);
      div += d[a];
      jac2 += glm::dot(d, d);
    }
    div_sum += std::abs(div);
    jac_sum += std::sqrt(jac2);
  }
  return div_sum / jac_sum;
}

double divergence_ratio2(const std::function<glm::vec2(glm::vec2)>& v, uint32_t seed) {
  return divergence_ratio3([&](glm::vec3 p) { return glm::vec3(v({p.x, p.y}), 0.0f); }, seed);
}

TEST(Curl3, IsDivergenceFree) {
  const glm::ivec3 period(4, 4, 8);
  const double curl = divergence_ratio3([&](glm::vec3 p) { return curl3(p, period, 3, 5u); }, 1);
  const double gradient = divergence_ratio3(
      [&](glm::vec3 p) { return curl3_potential(0, p, period, 3, 5u).gradient; }, 1);
  // Central differences in float: truncation (h k)^2 and rounding 1e-7 / h
  // relative to |J| ~ 10 leave ~1e-4; a gradient field has div = laplacian.
  EXPECT_LT(curl, 1e-3);
  EXPECT_GT(gradient, 0.1);
}

TEST(Curl2, IsDivergenceFreeAndOrthogonalToThePotentialGradient) {
  const glm::ivec2 period(8, 4);
  EXPECT_LT(divergence_ratio2([&](glm::vec2 p) { return curl2(p, period, 4, 6u); }, 2), 1e-3);
  EXPECT_GT(
      divergence_ratio2([&](glm::vec2 p) { return curl2_potential(p, period, 4, 6u).gradient; }, 2),
      0.1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 8.0f);
  for (int i = 0; i < 200; ++i) {
    const glm::vec2 p(u(rng), u(rng));
    const glm::vec2 g = curl2_potential(p, period, 4, 6u).gradient;
    const glm::vec2 v = curl2(p, period, 4, 6u);
    EXPECT_NEAR(glm::dot(v, g), 0.0f, 1e-5f * (1 + glm::dot(g, g)));
    EXPECT_NEAR(glm::length(v), glm::length(g), 1e-5f * (1 + glm::length(g)));
  }
}

TEST(Curl, RepeatsWithThePeriodForEveryOctaveCount) {
  std::mt19937 rng(4);
  for (int octaves = 1; octaves <= 4; ++octaves) {
    for (int i = 0; i < 50; ++i) {
      const glm::vec3 p(dyadic(rng, -5, 5), dyadic(rng, -5, 5), dyadic(rng, -5, 5));
      const glm::vec3 v = curl3(p, glm::ivec3(2, 3, 4), octaves, 8u);
      const glm::vec2 w = curl2({p.x, p.y}, glm::ivec2(3, 2), octaves, 8u);
      for (int a = 0; a < 3; ++a) {
        glm::vec3 q = p;
        q[a] += float(a + 2);  // the period of axis a is a + 2
        ASSERT_EQ(curl3(q, glm::ivec3(2, 3, 4), octaves, 8u), v) << "axis " << a;
      }
      ASSERT_EQ(curl2({p.x - 3, p.y}, glm::ivec2(3, 2), octaves, 8u), w);
      ASSERT_EQ(curl2({p.x, p.y + 2}, glm::ivec2(3, 2), octaves, 8u), w);
    }
  }
}

TEST(Curl3, PotentialsAreDecorrelated) {
  // Three copies of one potential would give a curl along (1, 1, 1) x grad:
  // orthogonal to (1, 1, 1). Decorrelated potentials do not.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  double along = 0, total = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 v = curl3({u(rng), u(rng), u(rng)}, glm::ivec3(4), 2, 9u);
    along += std::abs(v.x + v.y + v.z) / std::sqrt(3.0);
    total += glm::length(v);
  }
  EXPECT_GT(along / total, 0.2);
}

}  // namespace
}  // namespace skybake

// Tests of the ray / sphere distances (atmosphere/geometry.hpp) against the
// closed forms of simple rays and the defining property of each distance (the
// point it reaches lies on the sphere).
#include "atmosphere/geometry.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace skybake {
namespace {

constexpr double kRb = 6360e3, kRt = 6460e3;

TEST(DistanceToTopBoundary, VerticalUpIsRtMinusR) {
  for (double r : {kRb, kRb + 1.0, kRb + 30e3, kRt})
    EXPECT_NEAR(distance_to_top_boundary(kRt, r, 1.0), kRt - r, 1e-9 * kRt) << r;
  EXPECT_EQ(distance_to_top_boundary(kRt, kRt, 1.0), 0.0);
}

TEST(DistanceToTopBoundary, HorizontalIsPythagoras) {
  // mu = 0: the ray, the radius r and the exit radius Rt form a right triangle.
  for (double r : {kRb, kRb + 1.0, kRb + 30e3, kRt})
    EXPECT_NEAR(distance_to_top_boundary(kRt, r, 0.0), std::sqrt(kRt * kRt - r * r), 1e-6) << r;
}

TEST(DistanceToTopBoundary, StraightDownCrossesTheWholeSphere) {
  // mu = -1 along the line through the centre: r to the centre, then Rt.
  EXPECT_NEAR(distance_to_top_boundary(kRt, kRb + 5e3, -1.0), kRb + 5e3 + kRt, 1e-6);
}

TEST(DistanceToTopBoundary, EndsOnTheTopSphere) {
  for (double r : {kRb, kRb + 10e3, kRt - 1.0})
    for (double mu = -1.0; mu <= 1.0; mu += 0.125) {
      const double d = distance_to_top_boundary(kRt, r, mu);
      EXPECT_GE(d, 0.0);
      EXPECT_NEAR(radius_after(r, mu, d), kRt, 1e-9 * kRt) << r << " " << mu;
    }
}

TEST(DistanceToTopBoundary, TinyPlanet) {
  // 1 km planet, 200 m atmosphere: from the ground, straight up is 200 m and
  // horizontally sqrt(1200^2 - 1000^2) = sqrt(440000) m.
  EXPECT_NEAR(distance_to_top_boundary(1200.0, 1000.0, 1.0), 200.0, 1e-12);
  EXPECT_NEAR(distance_to_top_boundary(1200.0, 1000.0, 0.0), std::sqrt(440000.0), 1e-9);
}

TEST(RayIntersectsGround, Cases) {
  const double r = kRb + 10e3;
  // Horizon cosine: the ray tangent to the ground, mu_h = -sqrt(1 - Rb^2 / r^2).
  const double mu_h = -std::sqrt(1.0 - (kRb / r) * (kRb / r));
  EXPECT_TRUE(ray_intersects_ground(kRb, r, -1.0));
  EXPECT_TRUE(ray_intersects_ground(kRb, r, -0.5));
  EXPECT_TRUE(ray_intersects_ground(kRb, r, mu_h - 1e-6));
  EXPECT_FALSE(ray_intersects_ground(kRb, r, mu_h + 1e-6));
  EXPECT_FALSE(ray_intersects_ground(kRb, r, 0.0));
  EXPECT_FALSE(ray_intersects_ground(kRb, r, 0.5));
  EXPECT_FALSE(ray_intersects_ground(kRb, r, 1.0));
  // On the ground every downward ray hits it, every upward one misses.
  EXPECT_TRUE(ray_intersects_ground(kRb, kRb, -1e-9));
  EXPECT_FALSE(ray_intersects_ground(kRb, kRb, 1e-9));
}

TEST(DistanceToBottomBoundary, StraightDownIsRMinusRb) {
  for (double r : {kRb + 1.0, kRb + 30e3, kRt})
    EXPECT_NEAR(distance_to_bottom_boundary(kRb, r, -1.0), r - kRb, 1e-9 * kRt) << r;
  EXPECT_EQ(distance_to_bottom_boundary(kRb, kRb, -1.0), 0.0);
}

TEST(DistanceToBottomBoundary, EndsOnTheGround) {
  const double r = kRb + 10e3;
  const double mu_h = -std::sqrt(1.0 - (kRb / r) * (kRb / r));
  for (double mu : {-1.0, -0.5, -0.1, mu_h - 1e-4}) {
    ASSERT_TRUE(ray_intersects_ground(kRb, r, mu));
    const double d = distance_to_bottom_boundary(kRb, r, mu);
    EXPECT_GT(d, 0.0);
    EXPECT_NEAR(radius_after(r, mu, d), kRb, 1e-9 * kRb) << mu;
    // It is the first hit: the point halfway is above the ground.
    EXPECT_GT(radius_after(r, mu, 0.5 * d), kRb);
  }
}

TEST(DistanceToNearestBoundary, PicksGroundOrTop) {
  const double r = kRb + 1e3;
  EXPECT_EQ(distance_to_nearest_boundary(kRb, kRt, r, -1.0, true),
            distance_to_bottom_boundary(kRb, r, -1.0));
  EXPECT_EQ(distance_to_nearest_boundary(kRb, kRt, r, 0.3, false),
            distance_to_top_boundary(kRt, r, 0.3));
}

TEST(RadiusAfter, LawOfCosines) {
  const double r = kRb + 2e3;
  // Straight up: r + d, still vertical.
  EXPECT_NEAR(radius_after(r, 1.0, 5e3), r + 5e3, 1e-6);
  EXPECT_NEAR(mu_after(r, 1.0, 5e3, radius_after(r, 1.0, 5e3)), 1.0, 1e-15);
  // Horizontal: a right triangle, the new zenith cosine is d / r_d.
  const double r_d = radius_after(r, 0.0, 300e3);
  EXPECT_NEAR(r_d, std::hypot(r, 300e3), 1e-6);
  EXPECT_NEAR(mu_after(r, 0.0, 300e3, r_d), 300e3 / r_d, 1e-15);
  // Past the perigee of a descending ray the ray climbs again, symmetrically:
  // at d = -2 r mu it is back at radius r with cosine -mu.
  const double mu = -0.05, d = -2.0 * r * mu;
  EXPECT_NEAR(radius_after(r, mu, d), r, 1e-6);
  EXPECT_NEAR(mu_after(r, mu, d, radius_after(r, mu, d)), -mu, 1e-12);
}

}  // namespace
}  // namespace skybake

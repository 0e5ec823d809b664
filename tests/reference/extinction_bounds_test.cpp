// Tests of reference/extinction_bounds.hpp: the bins' bounds hold sigma_t on
// a fine grid and are tight where the extinction is monotone; the walk of a
// ray through the bins covers it exactly, each segment inside its bin.
#include "reference/extinction_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "support/test_atmospheres.hpp"
#include "reference/counter_rng.hpp"

namespace skybake {
namespace {

Atmosphere earth_with_bump() {
  // A concave layer with its maximum inside the lowest kilometre.
  DensityLayer l;
  l.exp_term = -1.0;
  l.exp_scale_per_m = 1e-3;
  l.linear_term_per_m = 2e-3;
  l.constant_term = 2.5 - 2.0 * std::log(2.0);
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.components.push_back(
      fixtures::make_component("bump", glm::dvec3(1e-6), glm::dvec3(2e-6), {{l}}));
  return atm;
}

void expect_bounds_hold(const Atmosphere& atm, const ExtinctionBounds& bounds) {
  for (int k = 0; k < bounds.bins(); ++k) {
    const double lo = bounds.boundary_altitude_m(k), hi = bounds.boundary_altitude_m(k + 1);
    ASSERT_LT(lo, hi);
    for (int i = 0; i < 200; ++i) {  // the ceiling belongs to the next bin
      const double h = lo + (hi - lo) * i / 200.0;
      const glm::dvec3 sigma_t = extinction_at(atm, h);
      for (int c = 0; c < 3; ++c) {
        ASSERT_LE(bounds.lower(k)[c], sigma_t[c]) << k << " " << h;
        ASSERT_GE(bounds.upper(k)[c], sigma_t[c]) << k << " " << h;
      }
    }
  }
}

TEST(ExtinctionBounds, HoldSigmaTInEveryBin) {
  for (const Atmosphere& atm :
       {fixtures::earth_atmosphere(), earth_with_bump(), fixtures::tiny_planet_atmosphere()}) {
    expect_bounds_hold(atm, ExtinctionBounds(atm, 64));
    expect_bounds_hold(atm, ExtinctionBounds(atm, AdaptiveBinning{}));
  }
}

// Adaptive bins meet their criterion, end at every kink, and spend few bins
// where the air is thin.
TEST(ExtinctionBounds, AdaptiveBinsMeetTheirCriterion) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const AdaptiveBinning binning;
  const ExtinctionBounds bounds(atm, binning);
  EXPECT_GT(bounds.bins(), 20);
  EXPECT_LT(bounds.bins(), 400);
  std::vector<double> floors;
  for (int k = 0; k <= bounds.bins(); ++k) floors.push_back(bounds.boundary_altitude_m(k));
  for (double kink : {10e3, 25e3, 40e3}) {  // the ozone tent
    const auto at = std::find_if(floors.begin(), floors.end(),
                                 [&](double h) { return std::abs(h - kink) < 1e-6; });
    EXPECT_NE(at, floors.end()) << kink;
  }
  EXPECT_EQ(floors.front(), 0.0);
  EXPECT_EQ(floors.back(), 100e3);
  int above_60km = 0;
  for (int k = 0; k < bounds.bins(); ++k) {
    const double lo = floors[size_t(k)], hi = floors[size_t(k) + 1];
    const double chord = 2.0 * std::sqrt((hi - lo) * (2.0 * atm.bottom_radius_m + hi + lo));
    for (int c = 0; c < 3; ++c) {
      const double spread = bounds.upper(k)[c] - bounds.lower(k)[c];
      EXPECT_TRUE(spread <= 1.001 * binning.max_relative_spread * bounds.upper(k)[c] ||
                  spread * chord <= 1.001 * binning.max_chord_spread)
          << k;
    }
    if (lo >= 60e3) ++above_60km;
  }
  EXPECT_LE(above_60km, 2);
}

// Earth's Rayleigh and Mie decrease with altitude and the ozone is 0 low
// down: the lowest bin's bounds are sigma_t at its bottom and top.
TEST(ExtinctionBounds, TightWhereMonotone) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const ExtinctionBounds bounds(atm, 64);
  const glm::dvec3 bottom = extinction_at(atm, 0.0);
  const glm::dvec3 top = extinction_at(atm, bounds.boundary_altitude_m(1));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(bounds.upper(0)[c], bottom[c], 1e-8 * bottom[c]);
    EXPECT_NEAR(bounds.lower(0)[c], top[c], 1e-8 * top[c]);
  }
}

TEST(ExtinctionBounds, EmptyAtmosphereIsZero) {
  const ExtinctionBounds bounds(fixtures::empty_atmosphere(), 8);
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(bounds.lower(k), glm::dvec3(0.0));
    EXPECT_EQ(bounds.upper(k), glm::dvec3(0.0));
  }
  EXPECT_EQ(bounds.bin_of_altitude(-5.0), 0);
  EXPECT_EQ(bounds.bin_of_altitude(1e12), 7);
}

// Walks rays of every kind (up, down to the ground, grazing past a perigee,
// from the boundaries) and checks the segments: contiguous from 0 to the
// end, and the altitude at both ends and the middle of each inside its bin.
void expect_walks_cover_rays(const Atmosphere& atm, const ExtinctionBounds& bounds) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double floor3 = bounds.boundary_altitude_m(3);
  CounterRng rng(4, 0, 0);
  struct Ray {
    double r, mu;
  };
  std::vector<Ray> rays = {{rb, 1.0},          {rb, 0.0},          {rt, -1.0},
                           {rt, -0.05},        {rb + 20e3, -0.12}, {rb + floor3, -0.0001},
                           {rb + floor3, 0.5}, {rt, 0.3}};
  for (int i = 0; i < 300; ++i) rays.push_back({rb + (rt - rb) * rng(), 2.0 * rng() - 1.0});
  for (const Ray ray : rays) {
    const bool ground = ray_intersects_ground(rb, ray.r, ray.mu);
    const double t_end = distance_to_nearest_boundary(rb, rt, ray.r, ray.mu, ground);
    AltitudeBinWalker walker(bounds, ray.r, ray.mu, t_end);
    double t0, t1, previous = 0.0;
    int bin, segments = 0;
    while (walker.next(t0, t1, bin)) {
      ASSERT_EQ(t0, previous);
      ASSERT_GT(t1, t0);
      for (double t : {t0, 0.5 * (t0 + t1), t1}) {
        const double h = radius_after(ray.r, ray.mu, t) - rb;
        const double slack = 1e-6;  // rounding of r = 6.4e6 m
        ASSERT_GE(h, bounds.boundary_altitude_m(bin) - slack) << ray.r << " " << ray.mu;
        ASSERT_LE(h, bounds.boundary_altitude_m(bin + 1) + slack) << ray.r << " " << ray.mu;
      }
      previous = t1;
      ++segments;
    }
    EXPECT_EQ(previous, t_end);
    if (ray.r == rb && ray.mu == 1.0) {
      EXPECT_EQ(segments, bounds.bins());  // straight up: one segment per bin
    }
  }
}

// Walks rays of every kind (up, down to the ground, grazing past a perigee,
// from the boundaries) and checks the segments: contiguous from 0 to the
// end, and the altitude at both ends and the middle of each inside its bin.
TEST(AltitudeBinWalker, CoversTheRayBinByBin) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  expect_walks_cover_rays(atm, ExtinctionBounds(atm, 64));
  expect_walks_cover_rays(atm, ExtinctionBounds(atm, AdaptiveBinning{}));
}

}  // namespace
}  // namespace skybake

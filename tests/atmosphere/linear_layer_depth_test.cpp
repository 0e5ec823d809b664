// Tests of the closed-form optical depth of piecewise-linear density
// profiles (atmosphere/linear_layer_depth.hpp) against an independent fine
// quadrature: long double composite Gauss-Legendre on pieces cut, by this
// file's own formulas, at the perigee and where the ray crosses each kink
// altitude, sampling medium.cpp's density_at.
#include "atmosphere/linear_layer_depth.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

// int_a^b f(x) dx by 3-point Gauss-Legendre on n equal segments, in long double.
template <class F>
long double fine_gauss(F f, long double a, long double b, int n) {
  const long double node = std::sqrt(0.6L), h = (b - a) / n;
  long double sum = 0.0L;
  for (int i = 0; i < n; ++i) {
    const long double mid = a + (i + 0.5L) * h, half = 0.5L * h;
    sum += half * (5.0L * f(mid - half * node) + 8.0L * f(mid) + 5.0L * f(mid + half * node)) / 9.0L;
  }
  return sum;
}

TEST(RadiusExcessIntegral, MatchesAFineQuadrature) {
  // Ends given by their distance x from the perigee (the radius derived),
  // except where radii_exact: the radius R0 or R1 given, x derived.
  struct Case {
    double p, x0, x1, R;
    bool radii_exact = false;
  };
  const double rb = 6360e3;
  const Case cases[] = {
      {0.0, rb, rb + 100e3, rb},          // vertical: r = x
      {rb, 0.0, 1.0, rb},                 // grazing the ground, first metre
      {rb, 0.0, 1e3, rb},                 // grazing, first km (h ~ x^2 / 2R)
      {rb, 0.0, 1.13e6, rb},              // the whole horizon ray
      {rb + 10e3, 0.0, 5e5, rb},          // perigee on the tent's lower kink
      {4.5e6, 0.0, 0.0, rb, true},        // between two kinks far from the perigee (below)
      {rb - 3e5, 2.1e6, 2.2e6, rb},       // far from a low perigee
      {4.5e6, 4.5e6, 4.6e6, rb},          // mu ~ 0.7 from the ground
      {1e3, 0.0, 1e5, 1e3},               // 1 km planet, grazing
      {5e2, 1e3, 9e4, 1e3},               // 1 km planet, from above the ground
      {1e-3, 0.0, 2e3, 1e3},              // through (nearly) the centre
  };
  for (Case c : cases) {
    if (c.radii_exact) {  // mu ~ 0.7 from the ground, between the kinks at 10 and 25 km
      c.x0 = std::sqrt((rb + 10e3 - c.p) * (rb + 10e3 + c.p));
      c.x1 = std::sqrt((rb + 25e3 - c.p) * (rb + 25e3 + c.p));
    }
    const long double p2 = (long double)c.p * c.p;
    auto excess = [&](long double x) { return std::sqrt(x * x + p2) - (long double)c.R; };
    // Cut at p 2^k too: around x ~ p the integrand bends over p.
    long double exact = 0.0L, from = c.x0;
    for (long double cut = c.p; cut > 0.0L && cut < c.x1; cut *= 2.0L)
      if (cut > from) {
        exact += fine_gauss(excess, from, cut, 400);
        from = cut;
      }
    exact += fine_gauss(excess, from, c.x1, 4000);
    double r0 = std::sqrt(c.x0 * c.x0 + c.p * c.p), r1 = std::sqrt(c.x1 * c.x1 + c.p * c.p);
    if (c.radii_exact) {
      r0 = rb + 10e3;
      r1 = rb + 25e3;
    }
    const double value = radius_excess_integral(c.p, c.x0, r0, c.x1, r1, c.R, c.radii_exact);
    // Rounding: the inputs carry ~eps R of error in the radius, which is
    // ~eps R L in the integral, and the form subtracts terms of size R L.
    const double tolerance = 1e-13 * std::abs(double(exact)) + 2e-15 * c.R * (c.x1 - c.x0);
    EXPECT_NEAR(value, double(exact), tolerance) << "p " << c.p << " x " << c.x0 << ".." << c.x1;
  }
}

// Optical depth of `atm` along [0, d] of the ray (r, mu) by fine_gauss on
// pieces between the perigee and the crossings of the spheres Rb + h_k.
glm::dvec3 fine_optical_depth(const Atmosphere& atm, const std::vector<double>& kinks, double r,
                              double mu, double d) {
  const long double lr = r, lmu = mu;
  std::vector<long double> cuts = {0.0L, (long double)d};
  const long double perigee = -lr * lmu;
  if (perigee > 0.0L && perigee < d) cuts.push_back(perigee);
  for (double h : kinks) {
    const long double R = (long double)atm.bottom_radius_m + h;
    const long double disc = lr * lr * lmu * lmu + R * R - lr * lr;
    if (disc <= 0.0L) continue;
    for (long double s : {perigee - std::sqrt(disc), perigee + std::sqrt(disc)})
      if (s > 0.0L && s < d) cuts.push_back(s);
  }
  std::sort(cuts.begin(), cuts.end());
  glm::dvec3 tau(0.0);
  for (const MediumComponent& c : atm.components) {
    auto density = [&](long double s) {
      const long double h = std::sqrt(s * s + 2.0L * lr * lmu * s + lr * lr) - atm.bottom_radius_m;
      return (long double)density_at(c.density, double(std::max(h, 0.0L)));
    };
    long double sum = 0.0L;
    for (size_t i = 0; i + 1 < cuts.size(); ++i) sum += fine_gauss(density, cuts[i], cuts[i + 1], 400);
    tau += double(sum) * (c.scattering_per_m + c.absorption_per_m);
  }
  return tau;
}

struct LinearCase {
  const char* name;
  Atmosphere atm;
  std::vector<double> kinks;  // m, every kink altitude of its profiles
  // Where the density jumps, a ray grazing the sphere of the jump crosses
  // it at x = sqrt(r^2 mu^2 + R^2 - r^2), whose argument both integrals know
  // to ~eps (r mu)^2, so x to ~sqrt(eps) |r mu|: allow 4e-8 |r mu| of chord
  // (two crossings) there. The tent has no jump and no allowance.
  bool jumps = false;
};

std::vector<LinearCase> linear_cases() {
  std::vector<LinearCase> out;
  const glm::dvec3 ozone(0.650e-6, 1.881e-6, 0.085e-6);
  out.push_back({"tent", fixtures::single_component_atmosphere(ozone, tent_profile(10e3, 25e3, 40e3)),
                 {10e3, 25e3, 40e3}, false});
  Atmosphere small = out.back().atm;
  small.bottom_radius_m = 1e3;
  small.top_radius_m = 101e3;
  out.push_back({"tent over a 1 km planet", small, {10e3, 25e3, 40e3}, false});
  out.push_back({"slab aloft",
                 fixtures::single_component_atmosphere(glm::dvec3(3e-5), uniform_profile(10e3, 25e3)),
                 {10e3, 25e3}, true});
  // A ramp clamped at both ends (0 below 1 km, 1 above 6 km) under a
  // constant 0.5 from 30 km: kinks at 1, 6 and 30 km.
  DensityLayer ramp;
  ramp.width_m = 30e3;
  ramp.linear_term_per_m = 1.0 / 5e3;
  ramp.constant_term = -0.2;
  DensityLayer half;
  half.constant_term = 0.5;
  out.push_back({"clamped ramp",
                 fixtures::single_component_atmosphere(glm::dvec3(2e-5), DensityProfile{{ramp, half}}),
                 {1e3, 6e3, 30e3}, true});
  return out;
}

// Rays from several altitudes: up, slanted, horizontal, down to the ground
// or past a perigee, grazing each kink sphere (perigee on it and 1 m to
// either side), whole and cut short (ending before the perigee).
struct Segment {
  double r, mu, d;
};
std::vector<Segment> test_segments(const Atmosphere& atm, const std::vector<double>& kinks) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  std::vector<Segment> out;
  for (double h : {0.0, 5e3, 10e3, 17.5e3, 25e3, 39.999e3, 40e3, 60e3, rt - rb}) {
    const double r = rb + h;
    std::vector<double> mus = {1.0, 0.5, 0.1, 0.01, 0.0, -0.01, -0.05, -0.2, -1.0};
    mus.push_back(-std::sqrt(std::max(0.0, 1.0 - (rb / r) * (rb / r))));  // the horizon
    for (double k : kinks)
      for (double offset : {-1.0, 0.0, 1.0}) {
        const double R = rb + k + offset;
        if (R < r) mus.push_back(-std::sqrt(1.0 - (R / r) * (R / r)));
      }
    for (double mu : mus) {
      const bool ground = ray_intersects_ground(rb, r, mu);
      const double d = distance_to_nearest_boundary(rb, rt, r, mu, ground);
      if (!(d > 0.0)) continue;
      out.push_back({r, mu, d});
      out.push_back({r, mu, 0.3 * d});
    }
  }
  return out;
}

TEST(LinearLayerDepth, MatchesAFineQuadratureThroughTheKinks) {
  for (const LinearCase& c : linear_cases()) {
    const LinearLayerDepth linear(c.atm);
    ASSERT_FALSE(linear.empty()) << c.name;
    for (const Segment& s : test_segments(c.atm, c.kinks)) {
      const glm::dvec3 exact = fine_optical_depth(c.atm, c.kinks, s.r, s.mu, s.d);
      const glm::dvec3 value = linear.integrate(s.r, s.mu, s.d);
      const glm::dvec3 sigma = c.atm.components[0].absorption_per_m;
      const double allowance = c.jumps ? 4e-8 * std::abs(s.r * s.mu) : 0.0;
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(value[ch], exact[ch],
                    1e-11 * exact[ch] + sigma[ch] * (1e-13 * s.d + allowance))
            << c.name << ": r " << s.r << " mu " << s.mu << " d " << s.d;
    }
  }
}

TEST(LinearLayerDepth, IsWhatTheTableRuleIntegrates) {
  // An atmosphere of linear layers only: the 8-point rule samples nothing
  // and returns the closed form; the 3-point rule (the references) samples.
  for (const LinearCase& c : linear_cases()) {
    const LinearLayerDepth linear(c.atm);
    for (const Segment& s : test_segments(c.atm, c.kinks)) {
      EXPECT_EQ(compute_optical_depth(c.atm, s.r, s.mu, s.d, 6, SegmentRule::gauss8),
                linear.integrate(s.r, s.mu, s.d))
          << c.name;
    }
  }
}

TEST(LinearLayerDepth, LeavesExponentialComponentsOut) {
  // Earth: only the ozone is linear; Rayleigh's and Mie's exponentials are
  // not the closed form's, so it returns the ozone's optical depth alone.
  const Atmosphere earth = fixtures::earth_atmosphere();
  Atmosphere ozone = earth;
  ozone.components = {fixtures::earth_ozone()};
  const LinearLayerDepth all(earth), only(ozone);
  const double r = earth.bottom_radius_m + 2e3;
  for (double mu : {1.0, 0.2, -0.02}) {
    const double d = distance_to_top_boundary(earth.top_radius_m, r, mu);
    EXPECT_EQ(all.integrate(r, mu, d), only.integrate(r, mu, d)) << mu;
  }
  EXPECT_TRUE(LinearLayerDepth(fixtures::tiny_planet_atmosphere()).empty());
}

}  // namespace
}  // namespace skybake

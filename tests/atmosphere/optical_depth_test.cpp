// Tests of the optical depth behind the transmittance table
// (compute_optical_depth, atmosphere/transmittance_lut.hpp): its quadrature
// against closed forms for uniform slabs, exponential and tent layers, and
// against an independent brute-force integral; its rules' convergence, and
// segments that add up.
#include "atmosphere/transmittance_lut.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "support/transmittance_rays.hpp"

namespace skybake {
namespace {

// ---- Closed forms -----------------------------------------------------------

// Length of the part of the segment [0, d] of the ray (r, mu) inside the
// sphere of radius R. Points at distance s have radius^2 = s^2 + 2 r mu s + r^2
// (law of cosines), below R^2 for s between the roots
// s = -r mu -+ sqrt(r^2 mu^2 - r^2 + R^2); intersect that interval with [0, d].
double length_inside_sphere(double R, double r, double mu, double d) {
  const double disc = r * r * mu * mu + (R - r) * (R + r);
  if (disc <= 0.0) return 0.0;
  const double lo = std::max(0.0, -r * mu - std::sqrt(disc));
  const double hi = std::min(d, -r * mu + std::sqrt(disc));
  return std::max(0.0, hi - lo);
}

TEST(ComputeOpticalDepth, UniformSlabFillingTheShellIsSigmaTimesDistance) {
  // Constant sigma_t along the whole ray: tau = sigma_t d, T = exp(-sigma_t d),
  // d = -r mu + sqrt(r^2 (mu^2 - 1) + Rt^2). Gauss-Legendre is exact for a
  // constant, so only rounding remains.
  const glm::dvec3 sigma_s(1e-5, 2e-5, 0.0), sigma_a(0.0, 1e-5, 4e-5);
  for (const Atmosphere& atm :
       {fixtures::uniform_slab_atmosphere(sigma_s, sigma_a),
        fixtures::uniform_slab_atmosphere(sigma_s * 1e3, sigma_a * 1e3, 1e3, 1.2e3)}) {
    const glm::dvec3 sigma =
        atm.components[0].scattering_per_m + atm.components[0].absorption_per_m;
    for (const fixtures::Ray& ray : fixtures::domain_rays(atm)) {
      const double d = -ray.r * ray.mu + std::sqrt(ray.r * ray.r * (ray.mu * ray.mu - 1.0) +
                                                   atm.top_radius_m * atm.top_radius_m);
      const glm::dvec3 tau = compute_optical_depth_to_top(atm, ray.r, ray.mu, 40);
      const glm::dvec3 T = compute_transmittance_to_top(atm, ray.r, ray.mu, 40);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(tau[c], sigma[c] * d, 1e-11 * sigma[c] * d + 1e-12) << ray.r << " " << ray.mu;
        EXPECT_NEAR(T[c], std::exp(-sigma[c] * d), 1e-11) << ray.r << " " << ray.mu;
      }
    }
  }
}

TEST(ComputeOpticalDepth, UniformSlabAloftIsSigmaTimesChordLength) {
  // A slab of constant sigma between 10 and 25 km: tau = sigma times the
  // length of the ray between the spheres Rb + 10 km and Rb + 25 km, i.e.
  // inside(Rb + 25 km) - inside(Rb + 10 km). The slab's edges are kinks of
  // the integrand that no smooth rule integrates well unless it cuts the ray
  // there, for rays that cross the slab at any angle, twice or not at all.
  const double sigma = 3e-5;
  const Atmosphere atm =
      fixtures::single_component_atmosphere(glm::dvec3(sigma), uniform_profile(10e3, 25e3));
  const double r1 = atm.bottom_radius_m + 10e3, r2 = atm.bottom_radius_m + 25e3;
  std::vector<fixtures::Ray> rays = fixtures::domain_rays(atm);
  for (double h : {5e3, 12e3, 20e3, 30e3, 60e3})  // perigees below, inside and above the slab
    for (double mu : {-0.2, -0.1, -0.08, -0.05, -0.02})
      if (mu > fixtures::mu_horizon(atm, atm.bottom_radius_m + h))
        rays.push_back({atm.bottom_radius_m + h, mu});
  for (const fixtures::Ray& ray : rays) {
    const double d = distance_to_top_boundary(atm.top_radius_m, ray.r, ray.mu);
    const double chord =
        length_inside_sphere(r2, ray.r, ray.mu, d) - length_inside_sphere(r1, ray.r, ray.mu, d);
    const glm::dvec3 tau = compute_optical_depth_to_top(atm, ray.r, ray.mu, 40);
    EXPECT_NEAR(tau.g, sigma * chord, 1e-9 * sigma * d) << ray.r << " " << ray.mu;
  }
}

// Vertical ray (mu = 1) from altitude h0 through one exponential layer:
//   tau = int_{h0}^{Ht} sigma exp(-h / H) dh = sigma H (exp(-h0 / H) - exp(-Ht / H)),
// Ht = Rt - Rb.
double exponential_vertical_tau(double sigma, double H, double h0, double top_h) {
  return sigma * H * (std::exp(-h0 / H) - std::exp(-top_h / H));
}

// Along the vertical from r, each doubling of the steps (the first count
// must show an error) divides the error by far more than 8 until it meets
// rounding: both rules converge faster than 3rd order.
void expect_converges_along_vertical(const Atmosphere& atm, double r, double exact,
                                     SegmentRule rule, std::vector<int> doublings) {
  auto error = [&](int steps) {
    return std::abs(compute_optical_depth_to_top(atm, r, 1.0, steps, rule).r - exact);
  };
  double previous = error(doublings.front());
  EXPECT_GT(previous, 1e-12 * exact) << doublings.front() << " steps should show an error";
  for (size_t i = 1; i < doublings.size(); ++i) {
    const double e = error(doublings[i]);
    if (previous > 1e-11 * exact) {
      EXPECT_LT(e, previous / 8.0) << "r " << r << " steps " << doublings[i];
    }
    previous = e;
  }
}

// Calls f(atm, r, exact optical depth) for vertical rays from three
// altitudes through one exponential layer of scale height 1.2 or 8 km.
void for_each_exponential_vertical(
    const std::function<void(const Atmosphere&, double r, double exact)>& f) {
  const double sigma = 1e-5;
  for (double H : {1.2e3, 8e3}) {
    const Atmosphere atm =
        fixtures::single_component_atmosphere(glm::dvec3(sigma), exponential_profile(H));
    const double top_h = atm.top_radius_m - atm.bottom_radius_m;
    for (double h0 : {0.0, 1e3, 30e3})
      f(atm, atm.bottom_radius_m + h0, exponential_vertical_tau(sigma, H, h0, top_h));
  }
}

TEST(ComputeOpticalDepth, ExponentialAlongTheVertical) {
  for_each_exponential_vertical([](const Atmosphere& atm, double r, double exact) {
    // Default steps: within 1e-6 relative.
    EXPECT_NEAR(compute_optical_depth_to_top(atm, r, 1.0, 40).r, exact, 1e-6 * exact) << "r " << r;
    // Convergence: composite 3-point Gauss-Legendre is 6th order.
    expect_converges_along_vertical(atm, r, exact, SegmentRule::gauss3, {5, 10, 20, 40, 80});
  });
}

TEST(ComputeOpticalDepth, OzoneTentAlongTheVertical) {
  // Tent 0 at 10 km, 1 at 25 km, 0 at 40 km; along the vertical h = h0 + s,
  // so tau / sigma is the area under the tent above h0:
  //   h0 = 0:       the whole triangle, 30 km * 1 / 2 = 15 km;
  //   h0 = 17.5 km: int_{17.5}^{25} (h - 10)/15 dh + 7.5 km
  //                 = (15^2 - 7.5^2) / 30 km + 7.5 km = 13.125 km;
  //   h0 = 30 km:   int_{30}^{40} (40 - h)/15 dh = 10^2 / 30 km = 10/3 km;
  //   h0 = 45 km:   0.
  const glm::dvec3 sigma(0.650e-6, 1.881e-6, 0.085e-6);
  const Atmosphere atm =
      fixtures::single_component_atmosphere(sigma, tent_profile(10e3, 25e3, 40e3));
  const std::pair<double, double> cases[] = {
      {0.0, 15e3}, {17.5e3, 13.125e3}, {30e3, 10e3 / 3.0}, {45e3, 0.0}};
  for (const auto& [h0, area] : cases) {
    const glm::dvec3 tau = compute_optical_depth_to_top(atm, atm.bottom_radius_m + h0, 1.0, 40);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(tau[c], sigma[c] * area, 1e-10 * sigma[c] * 15e3) << "h0 " << h0 << " c " << c;
  }
}

// An integrator that shares nothing with the one under test: the midpoint
// rule on a uniform partition of n steps, converged for n = 1e5 on Earth
// (error ~ (ds / H_mie)^2 / 24 < 1e-7 with ds <= 1.2 m on vertical rays;
// smaller on slanted ones, where the density varies more slowly along s).
glm::dvec3 brute_force_optical_depth(const Atmosphere& atm, double r, double mu, double d, int n) {
  glm::dvec3 tau(0.0);
  const double ds = d / n;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * ds;
    const double h = std::sqrt(s * s + 2.0 * r * mu * s + r * r) - atm.bottom_radius_m;
    tau += extinction_at(atm, std::max(h, 0.0)) * ds;
  }
  return tau;
}

TEST(ComputeOpticalDepth, EarthMatchesABruteForceIntegral) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const double rb = atm.bottom_radius_m;
  const fixtures::Ray rays[] = {{rb, 1.0},          {rb, 0.3},
                      {rb, 0.02},         {rb, 0.0},
                      {rb + 1e3, 0.5},    {rb + 15e3, fixtures::mu_horizon(atm, rb + 15e3)},
                      {rb + 15e3, -0.05}, {rb + 30e3, -0.08},
                      {rb + 60e3, 0.1},   {atm.top_radius_m, -0.1}};
  double max_error[4] = {0, 0, 0, 0};
  const int steps[4] = {10, 20, 40, 80};
  for (const fixtures::Ray& ray : rays) {
    const double d = distance_to_top_boundary(atm.top_radius_m, ray.r, ray.mu);
    const glm::dvec3 reference = brute_force_optical_depth(atm, ray.r, ray.mu, d, 100000);
    for (int i = 0; i < 4; ++i) {
      const glm::dvec3 tau = compute_optical_depth_to_top(atm, ray.r, ray.mu, steps[i]);
      for (int c = 0; c < 3; ++c)
        max_error[i] = std::max(max_error[i], std::abs(tau[c] - reference[c]) / reference[c]);
    }
  }
  EXPECT_LT(max_error[2], 1e-5) << "default 40 steps";
  EXPECT_GT(max_error[0], max_error[1]);
  EXPECT_GT(max_error[1], max_error[2]);
}

// The table's rule (8-point segments, default 6 steps) is at least as exact
// as the 3-point rule at 40 steps, the previous default, on every texel
// centre of a 256 x 64 table (a subset) of Earth, a Mars-like sky, the tiny
// planet, a 1 km planet under a 100 km atmosphere and Earth with 100x
// Rayleigh: the error of T against the 3-point rule at 400 steps, relative
// and floored at 1e-3 as the error records floor it.
TEST(ComputeOpticalDepth, TableRuleIsAsExactAsFortyThreePointSteps) {
  Atmosphere mars;
  mars.bottom_radius_m = 3386.19e3;
  mars.top_radius_m = mars.bottom_radius_m + 76.98e3;
  mars.components = {
      fixtures::make_component("rayleigh", {19.918e-6, 13.57e-6, 5.75e-6}, glm::dvec3(0.0),
                               exponential_profile(10.44e3), PhaseKind::rayleigh),
      fixtures::make_component("mie", glm::dvec3(53.618e-6), glm::dvec3(0.55e-6),
                               exponential_profile(3.095e3), PhaseKind::cornette_shanks, 0.85)};
  Atmosphere planet_1km = fixtures::earth_atmosphere();
  planet_1km.bottom_radius_m = 1e3;
  planet_1km.top_radius_m = 101e3;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), mars, fixtures::tiny_planet_atmosphere(),
                                planet_1km, fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 100.0)}) {
    double old_error = 0.0, new_error = 0.0;
    for (int y = 0; y < 64; y += 3) {
      for (int x = 0; x < 256; x += 5) {
        double r = 0.0, mu = 0.0;
        r_mu_from_transmittance_uv(atm, {texel_center(x, 256), texel_center(y, 64)}, 256, 64, r,
                                   mu);
        const glm::dvec3 ref = compute_transmittance_to_top(atm, r, mu, 400);
        const glm::dvec3 old_rule = compute_transmittance_to_top(atm, r, mu, 40);
        const glm::dvec3 table =
            compute_transmittance_to_top(atm, r, mu, TransmittanceLutSpec{}.steps, SegmentRule::gauss8);
        for (int c = 0; c < 3; ++c) {
          const double floor = std::max(ref[c], 1e-3);
          old_error = std::max(old_error, std::abs(old_rule[c] - ref[c]) / floor);
          new_error = std::max(new_error, std::abs(table[c] - ref[c]) / floor);
        }
      }
    }
    EXPECT_LE(new_error, std::max(old_error, 1e-9)) << "Rb " << atm.bottom_radius_m;
    EXPECT_LT(new_error, 1e-5) << "Rb " << atm.bottom_radius_m;
  }
}

// The 8-point rule converges at 16th order along an exponential vertical:
// each doubling of the steps divides the error by far more than 8 until it
// meets rounding.
TEST(ComputeOpticalDepth, EightPointRuleConvergesAlongTheVertical) {
  for_each_exponential_vertical([](const Atmosphere& atm, double r, double exact) {
    EXPECT_NEAR(compute_optical_depth_to_top(atm, r, 1.0, 6, SegmentRule::gauss8).r, exact,
                1e-8 * exact)
        << "r " << r;
    expect_converges_along_vertical(atm, r, exact, SegmentRule::gauss8, {1, 2, 4, 8});
  });
}

TEST(ComputeOpticalDepth, SegmentsAddUp) {
  // tau(0, d) = tau(0, d1) + tau(d1, d), the second part started from the
  // point at d1: the decomposition lookup_transmittance relies on. The ray
  // (2 km, mu = -0.02) passes its perigee above the ground (mu_h = -0.025).
  const Atmosphere atm = fixtures::earth_atmosphere();
  const double r = atm.bottom_radius_m + 2e3, mu = -0.02, d1 = 150e3;
  const double d = distance_to_top_boundary(atm.top_radius_m, r, mu);
  const double r1 = radius_after(r, mu, d1), mu1 = mu_after(r, mu, d1, r1);
  const glm::dvec3 whole = compute_optical_depth(atm, r, mu, d, 400);
  const glm::dvec3 parts =
      compute_optical_depth(atm, r, mu, d1, 200) + compute_optical_depth(atm, r1, mu1, d - d1, 200);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(parts[c], whole[c], 1e-7 * whole[c]);
}

}  // namespace
}  // namespace skybake

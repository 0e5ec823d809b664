// Tests of reference/atmosphere_quadrature.hpp against closed forms: optical
// depth in a uniform slab, an exponential and the ozone tent; single
// scattering in a uniform slab for vertical rays; invariants (additivity,
// the planet's shadow, agreement of tolerances within the error estimate).
#include "reference/atmosphere_quadrature.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using fixtures::earth_atmosphere;
using fixtures::single_component_atmosphere;
using fixtures::uniform_slab_atmosphere;

constexpr double kTol = 1e-12;        // optical depth
constexpr double kTolSingle = 1e-11;  // single scattering (nested: the inner floor is 1e-13)

void expect_rel(glm::dvec3 value, glm::dvec3 exact, double rel, const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(value[c], exact[c], rel * std::abs(exact[c])) << what << c;
}

// ---- Optical depth ----------------------------------------------------------

// A uniform slab filling the shell: tau = sigma_t d along any ray inside it.
TEST(ReferenceOpticalDepth, UniformSlabIsSigmaTimesLength) {
  const glm::dvec3 sigma_s(1e-5, 2e-5, 3e-5), sigma_a(4e-6, 0.0, 1e-6);
  const Atmosphere atm = uniform_slab_atmosphere(sigma_s, sigma_a);
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  struct Ray {
    double r, mu;
  };
  for (const Ray ray : {Ray{rb, 1.0}, Ray{rb, 0.0}, Ray{rb + 3e3, -0.01}, Ray{rb + 50e3, 0.3},
                        Ray{rt, -0.9}, Ray{rb + 10.0, -0.05}}) {
    const bool ground = ray_intersects_ground(rb, ray.r, ray.mu);
    const double d = distance_to_nearest_boundary(rb, rt, ray.r, ray.mu, ground);
    for (double fraction : {1.0, 0.37, 1e-6}) {
      const auto tau = reference_optical_depth(atm, ray.r, ray.mu, fraction * d, kTol);
      EXPECT_TRUE(tau.converged);
      expect_rel(tau.value, (sigma_s + sigma_a) * (fraction * d), 1e-10, "slab");
    }
  }
}

// Vertical rays in an exponential: tau = sigma H (exp(-h0 / H) - exp(-h1 / H)).
TEST(ReferenceOpticalDepth, VerticalExponential) {
  const glm::dvec3 sigma(5.8e-6, 13.558e-6, 33.1e-6);
  const double scale = 8e3;
  const Atmosphere atm = single_component_atmosphere(sigma, exponential_profile(scale));
  const double rb = atm.bottom_radius_m;
  for (double h0 : {0.0, 1e3, 30e3}) {
    for (double h1 : {h0 + 1.0, h0 + 5e3, 100e3}) {
      const glm::dvec3 exact = sigma * scale * (std::exp(-h0 / scale) - std::exp(-h1 / scale));
      expect_rel(reference_optical_depth(atm, rb + h0, 1.0, h1 - h0, kTol).value, exact, 1e-10,
                 "up");
      expect_rel(reference_optical_depth(atm, rb + h1, -1.0, h1 - h0, kTol).value, exact, 1e-10,
                 "down");
    }
  }
}

// The ozone tent (0 at 10 km, 1 at 25 km, 0 at 40 km): area 15 km from the
// ground to the top; 25/3 km between 20 and 30 km.
TEST(ReferenceOpticalDepth, VerticalOzoneTent) {
  const glm::dvec3 sigma(0.650e-6, 1.881e-6, 0.085e-6);
  const Atmosphere atm = single_component_atmosphere(sigma, tent_profile(10e3, 25e3, 40e3));
  const double rb = atm.bottom_radius_m;
  expect_rel(reference_optical_depth(atm, rb, 1.0, 100e3, kTol).value, sigma * 15e3, 1e-10,
             "whole");
  expect_rel(reference_optical_depth(atm, rb + 20e3, 1.0, 10e3, kTol).value, sigma * (25e3 / 3.0),
             1e-10, "20-30");
  expect_rel(reference_optical_depth(atm, rb + 30e3, -1.0, 10e3, kTol).value, sigma * (25e3 / 3.0),
             1e-10, "30-20");
}

// Optical depth adds along a ray: tau(0, d) = tau(0, s) + tau(s, d), here on
// Earth for a ray descending through its perigee and the ozone layer.
TEST(ReferenceOpticalDepth, AdditiveAlongARay) {
  const Atmosphere atm = earth_atmosphere();
  const double r = atm.bottom_radius_m + 45e3, mu = -0.1;
  const double d = distance_to_top_boundary(atm.top_radius_m, r, mu);
  ASSERT_FALSE(ray_intersects_ground(atm.bottom_radius_m, r, mu));
  for (double s : {0.1 * d, 0.5 * d, 0.93 * d}) {
    const double r_s = radius_after(r, mu, s), mu_s = mu_after(r, mu, s, r_s);
    const glm::dvec3 whole = reference_optical_depth(atm, r, mu, d, kTol).value;
    const glm::dvec3 parts = reference_optical_depth(atm, r, mu, s, kTol).value +
                             reference_optical_depth(atm, r_s, mu_s, d - s, kTol).value;
    expect_rel(parts, whole, 1e-10, "additive");
  }
}

TEST(ReferenceTransmittance, SlabAndGround) {
  const glm::dvec3 sigma(1e-5, 2e-5, 3e-5);
  const Atmosphere atm = uniform_slab_atmosphere(sigma, glm::dvec3(0.0));
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const auto up = reference_transmittance_to_top(atm, rb, 1.0, kTol);
  expect_rel(up.value, glm::exp(-sigma * (rt - rb)), 1e-10, "zenith");
  const auto slant = reference_transmittance_to_top(atm, rb + 2e3, 0.2, kTol);
  expect_rel(slant.value, glm::exp(-sigma * distance_to_top_boundary(rt, rb + 2e3, 0.2)), 1e-10,
             "slant");
  // A ray into the ground is blocked.
  EXPECT_EQ(reference_transmittance_to_top(atm, rb + 2e3, -0.5, kTol).value, glm::dvec3(0.0));
  // The horizon ray grazes the ground: its length to the top is the
  // tangent's, sqrt(Rt^2 - Rb^2) on each side of the tangent point.
  const double r = rb + 2e3, mu_h = -std::sqrt(1.0 - (rb / r) * (rb / r));
  const double d = std::sqrt(r * r - rb * rb) + std::sqrt(rt * rt - rb * rb);
  for (double mu : {mu_h, std::nextafter(mu_h, -1.0), std::nextafter(mu_h, 0.0)})
    expect_rel(reference_transmittance_to_top(atm, r, mu, kTol).value, glm::exp(-sigma * d), 1e-9,
               "horizon");
}

// ---- Single scattering ------------------------------------------------------

struct Slab {
  glm::dvec3 sigma_s{2e-5, 3e-5, 5e-5};
  glm::dvec3 sigma_a{1e-6, 0.0, 4e-6};
  glm::dvec3 sun{2.0, 1.0, 0.5};
  Atmosphere atm() const {
    Atmosphere a = uniform_slab_atmosphere(sigma_s, sigma_a);
    a.sun_illuminance = sun;
    return a;
  }
  glm::dvec3 sigma_t() const { return sigma_s + sigma_a; }
  double thickness() const { return 100e3; }
};

// Viewer on the ground looking up, sun at the zenith: at height s the view
// transmittance exp(-sigma_t s) and the sun's exp(-sigma_t (H - s)) multiply
// to exp(-sigma_t H), so L = E sigma_s p(1) H exp(-sigma_t H).
TEST(ReferenceSingleScattering, SlabZenithSunLookingUp) {
  const Slab slab;
  const Atmosphere atm = slab.atm();
  const double h = slab.thickness();
  const glm::dvec3 exact =
      slab.sun * slab.sigma_s * rayleigh_phase(1.0) * h * glm::exp(-slab.sigma_t() * h);
  const auto l = reference_single_scattering(atm, atm.bottom_radius_m, 1.0, 1.0, 1.0, kTolSingle);
  EXPECT_TRUE(l.converged);
  expect_rel(l.value, exact, 1e-10, "up");
}

// Looking straight down from the top with the sun at the zenith (nu = -1): at
// depth s both transmittances are exp(-sigma_t s), so
// L = E sigma_s p(-1) (1 - exp(-2 sigma_t H)) / (2 sigma_t). The same from far
// above the atmosphere (the viewer is moved to the top).
TEST(ReferenceSingleScattering, SlabZenithSunLookingDown) {
  const Slab slab;
  const Atmosphere atm = slab.atm();
  const glm::dvec3 st = slab.sigma_t();
  const glm::dvec3 exact = slab.sun * slab.sigma_s * rayleigh_phase(-1.0) *
                           (1.0 - glm::exp(-2.0 * st * slab.thickness())) / (2.0 * st);
  for (double r : {atm.top_radius_m, atm.top_radius_m + 1000e3}) {
    const auto l = reference_single_scattering(atm, r, -1.0, 1.0, -1.0, kTolSingle);
    EXPECT_TRUE(l.converged);
    expect_rel(l.value, exact, 1e-10, "down");
  }
}

// Each component scatters with its own phase: a Rayleigh and a
// Cornette-Shanks slab, sun at the zenith, looking up.
TEST(ReferenceSingleScattering, ComponentsUseTheirOwnPhase) {
  const double h = 100e3;
  Atmosphere atm = uniform_slab_atmosphere(glm::dvec3(1e-5), glm::dvec3(0.0));
  atm.components.push_back(fixtures::make_component("mie", glm::dvec3(4e-6), glm::dvec3(1e-6),
                                                    uniform_profile(0.0, h),
                                                    PhaseKind::cornette_shanks, 0.8));
  const glm::dvec3 sigma_t(1e-5 + 5e-6);
  const glm::dvec3 exact = (1e-5 * rayleigh_phase(1.0) + 4e-6 * cornette_shanks_phase(1.0, 0.8)) *
                           h * glm::exp(-sigma_t * h);
  expect_rel(reference_single_scattering(atm, atm.bottom_radius_m, 1.0, 1.0, 1.0, kTolSingle).value,
             exact, 1e-10, "mixture");
}

// The phase-free groups of the same mixture: each is its own sigma_s times
// h exp(-sigma_t h), the other group's light left out.
TEST(ReferenceSingleScatteringPhaseFree, MixedSlabClosedForm) {
  const double h = 100e3;
  Atmosphere atm = uniform_slab_atmosphere(glm::dvec3(1e-5), glm::dvec3(0.0));
  atm.components.push_back(fixtures::make_component("mie", glm::dvec3(4e-6), glm::dvec3(1e-6),
                                                    uniform_profile(0.0, h),
                                                    PhaseKind::cornette_shanks, 0.8));
  const glm::dvec3 path = h * glm::exp(-glm::dvec3(1e-5 + 5e-6) * h);
  const double rb = atm.bottom_radius_m;
  expect_rel(reference_single_scattering_phase_free(atm, rb, 1.0, 1.0, 1.0,
                                                    ScatteringGroup::rayleigh, kTolSingle)
                 .value,
             1e-5 * path, 1e-10, "rayleigh");
  expect_rel(reference_single_scattering_phase_free(atm, rb, 1.0, 1.0, 1.0, ScatteringGroup::mie,
                                                    kTolSingle)
                 .value,
             4e-6 * path, 1e-10, "mie");
}

// On Earth: p_R S_R + p_M S_M is the radiance, across the sky, toward the
// ground and with the planet's shadow on the ray (the header's identity).
TEST(ReferenceSingleScatteringPhaseFree, GroupsRecombineToTheRadiance) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m, g = atm.components[1].g;
  struct View {
    double r, mu, mu_s, nu;
  };
  for (const View v : {View{rb, 0.5, 0.7, 0.6}, View{rb + 1.0, 0.02, 0.1, 0.95},
                       View{rb + 30e3, -0.4, 0.3, -0.2}, View{rb, 0.3, -0.05, 0.9}}) {
    const auto l = reference_single_scattering(atm, v.r, v.mu, v.mu_s, v.nu, 1e-9);
    const auto s_r = reference_single_scattering_phase_free(atm, v.r, v.mu, v.mu_s, v.nu,
                                                            ScatteringGroup::rayleigh, 1e-9);
    const auto s_m = reference_single_scattering_phase_free(atm, v.r, v.mu, v.mu_s, v.nu,
                                                            ScatteringGroup::mie, 1e-9);
    EXPECT_TRUE(s_r.converged && s_m.converged);
    expect_rel(rayleigh_phase(v.nu) * s_r.value + cornette_shanks_phase(v.nu, g) * s_m.value,
               l.value, 1e-8, "recombined");
    for (int c = 0; c < 3; ++c) EXPECT_GT(s_m.value[c], 0.0) << c;
  }
}

// Sun at the nadir, looking up from the ground: every point of the view ray
// is in the planet's shadow. Without the shadow (a transparent planet) the
// sun ray from height s crosses s of air, the planet, then H of air:
// L = E sigma_s p(-1) exp(-sigma_t H) (1 - exp(-2 sigma_t H)) / (2 sigma_t).
TEST(ReferenceSingleScattering, SunAtNadirShadowAndTransparentPlanet) {
  const Slab slab;
  const Atmosphere atm = slab.atm();
  const auto shadowed =
      reference_single_scattering(atm, atm.bottom_radius_m, 1.0, -1.0, -1.0, kTolSingle);
  EXPECT_EQ(shadowed.value, glm::dvec3(0.0));
  const glm::dvec3 st = slab.sigma_t();
  const double h = slab.thickness();
  const glm::dvec3 exact = slab.sun * slab.sigma_s * rayleigh_phase(-1.0) * glm::exp(-st * h) *
                           (1.0 - glm::exp(-2.0 * st * h)) / (2.0 * st);
  const auto transparent =
      reference_single_scattering(atm, atm.bottom_radius_m, 1.0, -1.0, -1.0, kTolSingle, false);
  EXPECT_TRUE(transparent.converged);
  expect_rel(transparent.value, exact, 1e-10, "transparent");
}

TEST(ReferenceSingleScattering, EmptyAndMissedAtmosphereGiveZero) {
  const Atmosphere empty = fixtures::empty_atmosphere();
  EXPECT_EQ(reference_single_scattering(empty, empty.bottom_radius_m, 0.5, 0.5, 1.0, 1e-8).value,
            glm::dvec3(0.0));
  const Atmosphere earth = earth_atmosphere();
  EXPECT_EQ(
      reference_single_scattering(earth, earth.top_radius_m + 10e3, 0.1, 0.5, 0.2, 1e-8).value,
      glm::dvec3(0.0));
}

// On Earth, where no closed form exists: a loose tolerance agrees with a
// tight one within its own error estimate, for views across the sky,
// toward the ground, and at sunset with the planet's shadow on the ray.
TEST(ReferenceSingleScattering, ErrorEstimateIsHonestOnEarth) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m;
  struct View {
    double r, mu, mu_s, nu;
  };
  for (const View v : {View{rb, 0.5, 0.7, 0.6}, View{rb + 1.0, 0.02, 0.1, 0.95},
                       View{rb + 30e3, -0.4, 0.3, -0.2}, View{rb, 0.3, -0.05, 0.9}}) {
    const auto loose = reference_single_scattering(atm, v.r, v.mu, v.mu_s, v.nu, 1e-4);
    const auto tight = reference_single_scattering(atm, v.r, v.mu, v.mu_s, v.nu, 1e-9);
    EXPECT_TRUE(loose.converged);
    EXPECT_TRUE(tight.converged);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(tight.value[c], 0.0);
      EXPECT_LE(std::abs(loose.value[c] - tight.value[c]), loose.error[c] + tight.error[c]) << c;
      EXPECT_LE(tight.error[c], 1e-8 * tight.value[c]) << c;
    }
  }
}

// Extreme cases (presets/extreme/): finite, non-negative, converged.
TEST(ReferenceSingleScattering, StiffCasesConverge) {
  Atmosphere dense = earth_atmosphere();
  dense.components[0].scattering_per_m *= 1000.0;
  Atmosphere sharp = earth_atmosphere();
  sharp.components[1].g = 0.999;
  Atmosphere tiny = earth_atmosphere();
  tiny.bottom_radius_m = 1e3;
  tiny.top_radius_m = 101e3;
  struct Case {
    const Atmosphere* atm;
    double altitude_m, mu, mu_s, nu;
  };
  for (const Case c : {Case{&dense, 0.0, 0.01, 0.05, 0.9}, Case{&dense, 50e3, -0.2, 0.3, 0.1},
                       Case{&sharp, 0.0, 0.5, 0.5, 1.0}, Case{&tiny, 0.0, 0.7, 0.5, 0.6},
                       Case{&tiny, 60e3, -0.99, 0.1, -0.2}, Case{&dense, 0.0, 1.0, -1.0, -1.0}}) {
    const auto l = reference_single_scattering(*c.atm, c.atm->bottom_radius_m + c.altitude_m, c.mu,
                                               c.mu_s, c.nu, 1e-6);
    EXPECT_TRUE(l.converged);
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(std::isfinite(l.value[k]));
      EXPECT_GE(l.value[k], 0.0);
      EXPECT_LE(l.error[k], 1e-6 * l.value[k] + 1e-300);
    }
  }
}

// The vector form is the (r, mu, mu_s, nu) form.
TEST(ReferenceSingleScattering, VectorFormMatches) {
  const Atmosphere atm = earth_atmosphere();
  const glm::dvec3 x(0.0, 0.0, atm.bottom_radius_m + 500.0);
  const glm::dvec3 v = glm::normalize(glm::dvec3(1.0, 0.2, 0.3));
  const glm::dvec3 s = glm::normalize(glm::dvec3(0.3, -0.5, 0.4));
  const auto a = reference_single_scattering(atm, x, v, s, 1e-8);
  const auto b = reference_single_scattering(atm, glm::length(x), v.z, s.z, glm::dot(v, s), 1e-8);
  expect_rel(a.value, b.value, 1e-14, "vector");
}

}  // namespace
}  // namespace skybake

// Tests of reference/path_tracer.hpp. Every expectation is exact or a
// confidence-interval statement with a fixed seed: |mean - truth| <= 4
// standard errors (ci95 / 1.96), where the truth is a closed form or the
// adaptive quadrature (reference/atmosphere_quadrature.hpp) to 1e-8.
//   - an empty atmosphere: sky 0 and ground albedo / pi E mu_s, exactly;
//   - a pure absorber: the ground seen through it (ratio and delta tracking);
//   - single-scattering mode against the quadrature on Earth (noon, horizon,
//     from 30 km toward the ground, sunset with the planet's shadow), with
//     the forced first collision at both ends of the view ray's 1 - T (an
//     atmosphere 1 m thick, 100x Rayleigh), and in a 100x Rayleigh
//     atmosphere with a sharp Mie peak;
//   - a furnace: under isotropic illumination (a sun of random direction), a
//     non-absorbing medium over a white ground sends back exactly what it
//     receives: 4 pi E[L] / E = 1 - T(view ray to space);
//   - determinism across thread counts and seeds; finite, non-negative
//     results in stiff cases.
#include "reference/path_tracer.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "atmosphere/geometry.hpp"
#include "support/test_atmospheres.hpp"
#include "pipeline/preset_loader.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "reference/counter_rng.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

using fixtures::earth_atmosphere;
using fixtures::make_component;

// A direction of elevation / azimuth (degrees) in the frame of a viewer on
// the z axis (up = z).
glm::dvec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

glm::dvec3 above_ground(const Atmosphere& atm, double altitude_m) {
  return {0.0, 0.0, atm.bottom_radius_m + altitude_m};
}

// |mean - truth| <= 4 standard errors per channel (+ a relative slack for the
// truth's own error), and the interval is informative (below `max_rel`).
void expect_within_ci(const RadianceEstimate& e, glm::dvec3 truth, double max_rel,
                      const char* what) {
  for (int c = 0; c < 3; ++c) {
    const double sigma = e.ci95[c] / 1.96;
    EXPECT_NEAR(e.mean[c], truth[c], 4.0 * sigma + 1e-7 * std::abs(truth[c]))
        << what << " channel " << c << " ci95 " << e.ci95[c];
    EXPECT_LE(e.ci95[c], max_rel * std::abs(truth[c])) << what << " channel " << c;
  }
}

TEST(RadianceAccumulator, MeanAndConfidenceInterval) {
  RadianceAccumulator a;
  for (double x : {1.0, 2.0, 3.0, 4.0}) a.add(glm::dvec3(x, 2 * x, 5.0));
  const RadianceEstimate e = a.estimate();
  EXPECT_EQ(e.samples, 4);
  EXPECT_DOUBLE_EQ(e.mean.x, 2.5);
  EXPECT_DOUBLE_EQ(e.ci95.x, 1.96 * std::sqrt(5.0 / 3.0 / 4.0));  // sample variance 5/3
  EXPECT_DOUBLE_EQ(e.ci95.y, 2.0 * e.ci95.x);
  EXPECT_EQ(e.ci95.z, 0.0);  // identical samples
  // Merging halves gives the same estimate.
  RadianceAccumulator lo, hi;
  lo.add(glm::dvec3(1.0));
  lo.add(glm::dvec3(2.0));
  hi.add(glm::dvec3(3.0));
  hi.add(glm::dvec3(4.0));
  lo.merge(hi);
  EXPECT_DOUBLE_EQ(lo.estimate().mean.x, 2.5);
  EXPECT_DOUBLE_EQ(lo.estimate().ci95.x, e.ci95.x);
  EXPECT_TRUE(std::isinf(RadianceAccumulator().estimate().ci95.x));
}

// No medium: the sky is black and the ground is the sun's diffuse
// reflection, albedo / pi E mu_s, in every sample (so the interval is 0).
TEST(PathTracer, EmptyAtmosphereIsExact) {
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.ground_albedo = {0.1, 0.3, 0.7};
  atm.sun_illuminance = {3.0, 2.0, 1.0};
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.samples = 256;
  const glm::dvec3 x = above_ground(atm, 1e3), sun = direction(40.0, 0.0);
  const RadianceEstimate sky = tracer.trace(x, direction(30.0, 10.0), sun, spec);
  EXPECT_EQ(sky.mean, glm::dvec3(0.0));
  EXPECT_EQ(sky.ci95, glm::dvec3(0.0));
  // Straight down: the ground point's normal is z, so mu_s = sin(40 deg).
  const RadianceEstimate ground = tracer.trace(x, direction(-90.0, 0.0), sun, spec);
  const glm::dvec3 exact = atm.ground_albedo / kPi * atm.sun_illuminance * std::sin(40.0 * kDeg);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ground.mean[c], exact[c], 1e-15 * exact[c]);
  EXPECT_EQ(ground.ci95, glm::dvec3(0.0));
  // From space, looking away from the planet: nothing.
  EXPECT_EQ(tracer.trace({0.0, 0.0, 2.0 * atm.top_radius_m}, {0.0, 0.0, 1.0}, sun, spec).mean,
            glm::dvec3(0.0));
}

// A pure absorber over a grey ground, seen obliquely from 2 km: the ground's
// reflection attenuated on the way down from the sun and up to the eye,
//   L = albedo / pi E mu_s(ground) T(sun -> ground) T(ground -> eye).
TEST(PathTracer, AbsorberSeenThroughMatchesTransmittance) {
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.ground_albedo = glm::dvec3(0.4);
  atm.components = {
      make_component("haze", glm::dvec3(0.0), {2e-5, 5e-5, 1e-4}, exponential_profile(3e3)),
      make_component("ozone", glm::dvec3(0.0), {6.5e-6, 1.9e-5, 8.5e-7},
                     tent_profile(10e3, 25e3, 40e3))};
  const glm::dvec3 x = above_ground(atm, 2e3), view = direction(-30.0, 0.0);
  const glm::dvec3 sun = direction(35.0, 120.0);
  const double r = glm::length(x), mu = view.z;
  const double d = distance_to_bottom_boundary(atm.bottom_radius_m, r, mu);
  const glm::dvec3 n = glm::normalize(x + d * view);
  const double mu_s = glm::dot(n, sun);
  const glm::dvec3 t_view = glm::exp(-reference_optical_depth(atm, r, mu, d, 1e-10).value);
  const glm::dvec3 t_sun =
      reference_transmittance_to_top(atm, atm.bottom_radius_m, mu_s, 1e-10).value;
  const glm::dvec3 truth = atm.ground_albedo / kPi * mu_s * t_sun * t_view;
  PathTracerSpec spec;
  spec.samples = 4096;
  expect_within_ci(trace_sky_radiance(atm, x, view, sun, spec), truth, 0.05, "absorber");
}

struct View {
  const char* name;
  double altitude_m, elevation_deg, azimuth_deg, sun_elevation_deg;
  double max_ci = 0.1;  // the interval must be this informative (relative)
};

// Single-scattering mode against the adaptive quadrature.
TEST(PathTracer, SingleScatteringMatchesQuadratureOnEarth) {
  const Atmosphere atm = earth_atmosphere();
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec = single_scattering_spec();
  spec.samples = 6000;
  for (const View v : {View{"noon", 0.0, 30.0, 90.0, 60.0}, View{"horizon", 1.0, 2.0, 20.0, 10.0},
                       View{"from 30 km down", 30e3, -20.0, 180.0, 25.0},
                       // Most collisions fall in the shadow and gather nothing.
                       View{"sunset shadow", 0.0, 15.0, 0.0, -3.0, 0.25}}) {
    const glm::dvec3 x = above_ground(atm, v.altitude_m),
                     w = direction(v.elevation_deg, v.azimuth_deg);
    const glm::dvec3 sun = direction(v.sun_elevation_deg, 0.0);
    const auto truth = reference_single_scattering(atm, x, w, sun, 1e-8);
    ASSERT_TRUE(truth.converged) << v.name;
    expect_within_ci(tracer.trace(x, w, sun, spec), truth.value, v.max_ci, v.name);
  }
}

// The forced first collision (drawn from the view ray's optical depth, see
// the header) in single-scattering mode against the quadrature, at both
// ends of 1 - T: the atmosphere 1 m thick (1 - T from ~1e-5 looking up to
// ~0.2 along the ground, where rejection needed up to 1e5 tries) and 100x
// Earth's Rayleigh (1 - T = 1 to rounding; the collision within a few
// hundred metres of a viewer on the ground, spread over many bins from
// above). The suns keep the sun's transmittance estimable (see the dense
// test below).
TEST(PathTracer, ForcedCollisionMatchesQuadratureInThinAndDenseAir) {
  struct Case {
    const char* preset;
    View v;
  };
  PathTracerSpec spec = single_scattering_spec();
  spec.samples = 4000;
  for (const Case& c :
       {Case{"atmosphere_1m", {"1 m: along the ground", 0.0, 0.0, 30.0, 10.0}},
        Case{"atmosphere_1m", {"1 m: 2 deg up", 0.0, 2.0, 150.0, 40.0}},
        Case{"atmosphere_1m", {"1 m: 60 deg up", 0.5, 60.0, 0.0, 30.0}},
        Case{"atmosphere_1m", {"1 m: from the top down", 1.0, -5.0, 90.0, 20.0}},
        Case{"rayleigh_100x", {"100x: 10 deg up", 0.0, 10.0, 0.0, 90.0}},
        Case{"rayleigh_100x", {"100x: from 60 km level", 60e3, 0.0, 45.0, 60.0}},
        Case{"rayleigh_100x", {"100x: from the top down", 100e3, -30.0, 0.0, 60.0}}}) {
    const Atmosphere atm =
        load_scene(test::source_path(std::string("presets/extreme/") + c.preset + ".json"))
            .atmosphere;
    const glm::dvec3 x = above_ground(atm, c.v.altitude_m),
                     w = direction(c.v.elevation_deg, c.v.azimuth_deg);
    const glm::dvec3 sun = direction(c.v.sun_elevation_deg, 0.0);
    const auto truth = reference_single_scattering(atm, x, w, sun, 1e-8);
    ASSERT_TRUE(truth.converged) << c.v.name;
    expect_within_ci(trace_sky_radiance(atm, x, w, sun, spec), truth.value, c.v.max_ci, c.v.name);
  }
}

// The same in a stiff medium: 100x Earth's Rayleigh (blue optical depth ~26
// to the zenith) and Mie with g = 0.95, looking near the sun. The sun's
// transmittance from the first collision is ~1e-4 (red) to ~1e-24 (blue),
// which residual ratio tracking estimates to ~15% with 6000 paths.
TEST(PathTracer, SingleScatteringMatchesQuadratureInDenseAir) {
  Atmosphere atm = earth_atmosphere();
  atm.components[0].scattering_per_m *= 100.0;
  atm.components[1].g = 0.95;
  const glm::dvec3 x = above_ground(atm, 0.0), w = direction(20.0, 5.0), sun = direction(30.0, 0.0);
  const auto truth = reference_single_scattering(atm, x, w, sun, 1e-8);
  ASSERT_TRUE(truth.converged);
  PathTracerSpec spec = single_scattering_spec();
  spec.samples = 6000;
  expect_within_ci(trace_sky_radiance(atm, x, w, sun, spec), truth.value, 0.25, "dense");
}

// Isotropic illumination of radiance L0 from every direction of space is a
// superposition of suns of illuminance L0 dl. A medium that does not absorb
// over a white ground (albedo 1) then has L = L0 everywhere (the uniform
// field solves the transfer equation), of which L0 T(view) arrives straight
// from space along the view ray and is not part of the traced radiance
// (the sun is excluded). Averaging over a uniform sun direction l:
//   4 pi E_l[L(l)] / E = 1 - T(view ray to space)   (1 toward the ground).
// Exact at any density and order: a test of energy conservation of the
// whole estimator (tracking, phase sampling weights, ground bounce,
// Russian roulette).
TEST(PathTracer, FurnaceUnderIsotropicIllumination) {
  Atmosphere atm = earth_atmosphere();
  atm.ground_albedo = glm::dvec3(1.0);
  atm.sun_illuminance = {1.0, 2.0, 0.5};
  atm.components = {make_component("rayleigh", glm::dvec3(3e-5, 6e-5, 1.2e-4), glm::dvec3(0.0),
                                   exponential_profile(8e3), PhaseKind::rayleigh),
                    make_component("mie", glm::dvec3(2e-5), glm::dvec3(0.0),
                                   exponential_profile(1.2e3), PhaseKind::cornette_shanks, 0.8)};
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.max_bounces = 100000;  // Russian roulette ends the paths
  struct FurnaceView {
    double altitude_m, elevation_deg;
  };
  for (const FurnaceView v : {FurnaceView{0.0, 10.0}, FurnaceView{5e3, -60.0}}) {
    const glm::dvec3 x = above_ground(atm, v.altitude_m), w = direction(v.elevation_deg, 0.0);
    glm::dvec3 truth(1.0);
    if (v.elevation_deg > 0.0)
      truth -= reference_transmittance_to_top(atm, glm::length(x), w.z, 1e-10).value;
    RadianceAccumulator acc;
    for (int k = 0; k < 3000; ++k) {
      CounterRng rng(11, uint64_t(k), 99);
      const double z = 2.0 * rng() - 1.0, phi = 2.0 * kPi * rng();
      const double s = std::sqrt(1.0 - z * z);
      const glm::dvec3 sun(s * std::cos(phi), s * std::sin(phi), z);
      acc.add(4.0 * kPi * tracer.trace_sample(x, w, sun, spec, uint64_t(k)) / atm.sun_illuminance);
    }
    expect_within_ci(acc.estimate(), truth, 0.1, v.elevation_deg > 0.0 ? "sky" : "ground");
  }
}

// Bit-identical for 1 and 2 threads; other seeds agree within the intervals.
TEST(PathTracer, DeterministicAcrossThreadsAndSeeds) {
  const Atmosphere atm = earth_atmosphere();
  const SkyPathTracer tracer(atm);
  const glm::dvec3 x = above_ground(atm, 0.0), w = direction(10.0, 30.0),
                   sun = direction(20.0, 0.0);
  PathTracerSpec spec;
  spec.samples = 1000;  // several chunks, one of them partial
  RadianceEstimate one, two;
  tbb::task_arena(1).execute([&] { one = tracer.trace(x, w, sun, spec); });
  tbb::task_arena(2).execute([&] { two = tracer.trace(x, w, sun, spec); });
  EXPECT_EQ(one.mean, two.mean);
  EXPECT_EQ(one.ci95, two.ci95);
  EXPECT_EQ(one.samples, 1000);
  spec.seed = 2;
  const RadianceEstimate other = tracer.trace(x, w, sun, spec);
  EXPECT_NE(other.mean, one.mean);
  for (int c = 0; c < 3; ++c) {
    const double sigma = std::hypot(one.ci95[c], other.ci95[c]) / 1.96;
    EXPECT_NEAR(other.mean[c], one.mean[c], 4.0 * sigma) << c;
  }
}

void expect_finite_non_negative(const Atmosphere& atm, glm::dvec3 x, glm::dvec3 w, glm::dvec3 sun,
                                const char* what) {
  PathTracerSpec spec;
  spec.samples = 64;
  const RadianceEstimate e = trace_sky_radiance(atm, x, w, sun, spec);
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(std::isfinite(e.mean[c])) << what;
    EXPECT_GE(e.mean[c], 0.0) << what;
    EXPECT_TRUE(std::isfinite(e.ci95[c])) << what;
  }
}

TEST(PathTracer, StiffCasesStayFiniteAndNonNegative) {
  Atmosphere dense = earth_atmosphere();
  dense.components[0].scattering_per_m *= 100.0;
  expect_finite_non_negative(dense, above_ground(dense, 0.0), direction(1.0, 0.0),
                             direction(5.0, 0.0), "100x Rayleigh");
  Atmosphere sharp = earth_atmosphere();
  sharp.components[1].g = 0.999;
  expect_finite_non_negative(sharp, above_ground(sharp, 0.0), direction(30.0, 0.0),
                             direction(30.0, 0.0), "g = 0.999 into the sun");
  Atmosphere backward = earth_atmosphere();
  backward.components[1].phase = PhaseKind::henyey_greenstein;
  backward.components[1].g = -0.9;
  expect_finite_non_negative(backward, above_ground(backward, 0.0), direction(30.0, 180.0),
                             direction(30.0, 0.0), "HG g = -0.9");
  Atmosphere tiny = earth_atmosphere();
  tiny.bottom_radius_m = 1e3;
  tiny.top_radius_m = 101e3;
  expect_finite_non_negative(tiny, above_ground(tiny, 0.0), direction(45.0, 0.0),
                             direction(30.0, 90.0), "1 km planet");
  expect_finite_non_negative(tiny, above_ground(tiny, 50e3), direction(-80.0, 0.0),
                             direction(30.0, 90.0), "1 km planet from above");
  const Atmosphere earth = earth_atmosphere();
  expect_finite_non_negative(earth, above_ground(earth, 0.0), direction(45.0, 0.0),
                             direction(-90.0, 0.0), "sun at the nadir");
  expect_finite_non_negative(earth, above_ground(earth, 0.0), direction(-45.0, 0.0),
                             direction(0.0, 0.0), "ground, sun on the horizon");
}

}  // namespace
}  // namespace skybake

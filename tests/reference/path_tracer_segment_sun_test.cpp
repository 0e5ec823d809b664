// Tests of the path tracer's segment estimate of the sun
// (SunEstimate::segment, reference/path_tracer.hpp) and of the shadow
// interval it draws on (reference/planet_shadow.hpp):
//   - the closed-form shadow interval against the point test (the sun ray
//     meets the ground) along random segments;
//   - single scattering with the sun 4 to 14 degrees below the horizon
//     against the deterministic quadrature (reference/atmosphere_quadrature.hpp),
//     where the lit air is a thin layer high above the shadow;
//   - the same in daylight and in a stiff medium, where the collision
//     estimate is the proven one;
//   - every order: the furnace's energy balance, and the collision estimate
//     in daylight within the two intervals.
// Expectations: |mean - truth| <= 4 standard errors, as in path_tracer_test.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "core/math.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "reference/counter_rng.hpp"
#include "reference/path_tracer.hpp"
#include "reference/planet_shadow.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

glm::dvec3 segment_sun_direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

glm::dvec3 segment_sun_uniform_direction(CounterRng& rng) {
  const double z = 2.0 * rng() - 1.0, phi = 2.0 * kPi * rng();
  const double s = std::sqrt(1.0 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

void expect_segment_within_ci(const RadianceEstimate& e, glm::dvec3 truth, double max_rel,
                              const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    const double sigma = e.ci95[c] / 1.96;
    EXPECT_NEAR(e.mean[c], truth[c], 4.0 * sigma + 1e-7 * std::abs(truth[c]))
        << what << " channel " << c << " ci95 " << e.ci95[c];
    EXPECT_LE(e.ci95[c], max_rel * std::abs(truth[c])) << what << " channel " << c;
  }
}

TEST(PlanetShadow, IntervalMatchesThePointTest) {
  const double rb = 6360e3, rt = 6460e3;
  CounterRng rng(5, 0, 0);
  int shadowed = 0, lit = 0;
  for (int k = 0; k < 400; ++k) {
    const glm::dvec3 origin = (rb + (rt - rb) * rng()) * segment_sun_uniform_direction(rng);
    const glm::dvec3 dir = segment_sun_uniform_direction(rng);
    const glm::dvec3 sun = segment_sun_uniform_direction(rng);
    const double length = 400e3 * rng();
    const ShadowInterval shadow = planet_shadow_interval(origin, dir, sun, rb, length);
    for (int i = 0; i <= 200; ++i) {
      const double s = length * i / 200.0;
      const glm::dvec3 p = origin + s * dir;
      const double r = glm::length(p);
      const bool blocked = ray_intersects_ground(rb, r, glm::dot(p, sun) / r);
      const bool inside = !shadow.empty() && s >= shadow.begin && s < shadow.end;
      // Within a metre of an end the two tests may round either way.
      const bool near_end =
          !shadow.empty() && (std::abs(s - shadow.begin) < 1.0 || std::abs(s - shadow.end) < 1.0);
      if (!near_end) {
        EXPECT_EQ(inside, blocked) << k << " " << s;
      }
      (blocked ? shadowed : lit) += 1;
    }
  }
  EXPECT_GT(shadowed, 1000);
  EXPECT_GT(lit, 1000);
}

struct TwilightView {
  double sun_zenith_deg, elevation_deg, azimuth_deg;
};

// Earth in twilight, single scattering: the segment estimate converges to
// the quadrature where the collision estimate's sum over thousands of paths
// is mostly zero (the path tracer's header).
TEST(PathTracerSegmentSun, SingleScatteringMatchesQuadratureInTwilight) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec = single_scattering_spec();
  spec.samples = 3000;
  spec.sun_estimate = SunEstimate::segment;
  const glm::dvec3 x(0.0, 0.0, atm.bottom_radius_m + 1.0);
  for (const TwilightView v : {TwilightView{94.0, 2.0, 0.0}, TwilightView{94.0, 10.0, 180.0},
                               TwilightView{94.0, 80.0, 90.0}, TwilightView{98.0, 10.0, 0.0},
                               TwilightView{98.0, 30.0, 90.0}, TwilightView{98.0, 80.0, 180.0},
                               TwilightView{104.0, 2.0, 0.0}}) {
    const double z = v.sun_zenith_deg * kDeg;
    const glm::dvec3 sun(std::sin(z), 0.0, std::cos(z));
    const glm::dvec3 w = segment_sun_direction(v.elevation_deg, v.azimuth_deg);
    const auto truth = reference_single_scattering(atm, x, w, sun, 1e-8);
    ASSERT_TRUE(truth.converged);
    ASSERT_GT(truth.value.b, 0.0);
    expect_segment_within_ci(tracer.trace(x, w, sun, spec), truth.value, 0.1,
                             std::to_string(v.sun_zenith_deg) + " " +
                                 std::to_string(v.elevation_deg) + " " +
                                 std::to_string(v.azimuth_deg));
  }
}

TEST(PathTracerSegmentSun, SingleScatteringMatchesQuadratureInDaylightAndDenseAir) {
  Atmosphere dense = fixtures::earth_atmosphere();
  dense.components[0].scattering_per_m *= 100.0;
  dense.components[1].g = 0.95;
  struct Case {
    Atmosphere atm;
    double altitude_m, elevation_deg, azimuth_deg, sun_elevation_deg, max_ci;
  };
  PathTracerSpec spec = single_scattering_spec();
  spec.samples = 3000;
  spec.sun_estimate = SunEstimate::segment;
  for (const Case& c : {Case{fixtures::earth_atmosphere(), 0.0, 30.0, 90.0, 60.0, 0.1},
                        Case{fixtures::earth_atmosphere(), 30e3, -20.0, 180.0, 25.0, 0.1},
                        Case{dense, 0.0, 20.0, 5.0, 30.0, 0.3}}) {
    const glm::dvec3 x(0.0, 0.0, c.atm.bottom_radius_m + c.altitude_m);
    const glm::dvec3 w = segment_sun_direction(c.elevation_deg, c.azimuth_deg);
    const glm::dvec3 sun = segment_sun_direction(c.sun_elevation_deg, 0.0);
    const auto truth = reference_single_scattering(c.atm, x, w, sun, 1e-8);
    ASSERT_TRUE(truth.converged);
    expect_segment_within_ci(trace_sky_radiance(c.atm, x, w, sun, spec), truth.value, c.max_ci,
                             std::to_string(c.elevation_deg));
  }
}

// Every order: the furnace of path_tracer_test.cpp (isotropic illumination
// over a white ground without absorption: 4 pi E_l[L(l)] / E = 1 - T(view
// ray to space)) with the segment estimate at every flight.
TEST(PathTracerSegmentSun, FurnaceUnderIsotropicIllumination) {
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.ground_albedo = glm::dvec3(1.0);
  atm.sun_illuminance = {1.0, 2.0, 0.5};
  atm.components = {
      fixtures::make_component("rayleigh", glm::dvec3(3e-5, 6e-5, 1.2e-4), glm::dvec3(0.0),
                               exponential_profile(8e3), PhaseKind::rayleigh),
      fixtures::make_component("mie", glm::dvec3(2e-5), glm::dvec3(0.0), exponential_profile(1.2e3),
                               PhaseKind::cornette_shanks, 0.8)};
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.max_bounces = 100000;
  spec.sun_estimate = SunEstimate::segment;
  for (const double elevation : {10.0, -60.0}) {
    const glm::dvec3 x(0.0, 0.0, atm.bottom_radius_m + (elevation > 0.0 ? 0.0 : 5e3));
    const glm::dvec3 w = segment_sun_direction(elevation, 0.0);
    glm::dvec3 truth(1.0);
    if (elevation > 0.0)
      truth -= reference_transmittance_to_top(atm, glm::length(x), w.z, 1e-10).value;
    RadianceAccumulator acc;
    for (int k = 0; k < 3000; ++k) {
      CounterRng rng(13, uint64_t(k), 99);
      const glm::dvec3 sun = segment_sun_uniform_direction(rng);
      acc.add(4.0 * kPi * tracer.trace_sample(x, w, sun, spec, uint64_t(k)) / atm.sun_illuminance);
    }
    expect_segment_within_ci(acc.estimate(), truth, 0.1, elevation > 0.0 ? "sky" : "ground");
  }
}

// Every order in daylight, Earth with its ground: the two estimates agree
// within their joint interval.
TEST(PathTracerSegmentSun, AgreesWithTheCollisionEstimateInDaylight) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SkyPathTracer tracer(atm);
  const glm::dvec3 x(0.0, 0.0, atm.bottom_radius_m + 1.0);
  PathTracerSpec spec;
  spec.samples = 3000;
  for (const double sun_elevation : {45.0, 5.0}) {
    const glm::dvec3 w = segment_sun_direction(20.0, 120.0);
    const glm::dvec3 sun = segment_sun_direction(sun_elevation, 0.0);
    spec.sun_estimate = SunEstimate::collision;
    const RadianceEstimate collision = tracer.trace(x, w, sun, spec);
    spec.sun_estimate = SunEstimate::segment;
    const RadianceEstimate segment = tracer.trace(x, w, sun, spec);
    for (int c = 0; c < 3; ++c) {
      const double sigma = std::hypot(collision.ci95[c], segment.ci95[c]) / 1.96;
      EXPECT_NEAR(segment.mean[c], collision.mean[c], 4.0 * sigma) << sun_elevation << " " << c;
      EXPECT_LT(segment.ci95[c], 0.05 * segment.mean[c]) << sun_elevation << " " << c;
    }
  }
}

}  // namespace
}  // namespace skybake

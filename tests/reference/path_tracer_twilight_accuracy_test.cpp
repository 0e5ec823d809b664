// The path tracer with every order in twilight (docs/testing.md accuracy
// tier): its two estimates of the sun (reference/path_tracer.hpp) are
// independent ways to the same expectation, so they must agree where both
// converge. With the sun 4 degrees below the horizon the collision estimate
// needs ~1e5 paths for a few percent; the segment estimate gets there with
// ~1e4. Views up, across and toward the sun from the ground on Earth.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/math.hpp"
#include "reference/path_tracer.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(PathTracerTwilightAccuracy, SegmentAndCollisionEstimatesAgreeWithEveryOrder) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SkyPathTracer tracer(atm);
  const glm::dvec3 x(0.0, 0.0, atm.bottom_radius_m + 1.0);
  const double z = 94.0 * kDeg;
  const glm::dvec3 sun(std::sin(z), 0.0, std::cos(z));
  struct View {
    double elevation_deg, azimuth_deg;
  };
  for (const View v : {View{30.0, 90.0}, View{80.0, 0.0}, View{5.0, 180.0}}) {
    const double e = v.elevation_deg * kDeg, a = v.azimuth_deg * kDeg;
    const glm::dvec3 w(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    PathTracerSpec spec;
    spec.samples = 200000;
    const RadianceEstimate collision = tracer.trace(x, w, sun, spec);
    spec.samples = 20000;
    spec.sun_estimate = SunEstimate::segment;
    const RadianceEstimate segment = tracer.trace(x, w, sun, spec);
    for (int c = 0; c < 3; ++c) {
      std::printf(
          "[ measured ] view %.0f/%.0f channel %d: collision %.4e +- %.1f%%, segment "
          "%.4e +- %.1f%%\n",
          v.elevation_deg, v.azimuth_deg, c, collision.mean[c],
          100.0 * collision.ci95[c] / collision.mean[c], segment.mean[c],
          100.0 * segment.ci95[c] / segment.mean[c]);
      const double sigma = std::hypot(collision.ci95[c], segment.ci95[c]) / 1.96;
      EXPECT_NEAR(segment.mean[c], collision.mean[c], 4.0 * sigma) << v.elevation_deg << " " << c;
      EXPECT_LT(segment.ci95[c], 0.1 * segment.mean[c]) << v.elevation_deg << " " << c;
    }
  }
}

}  // namespace
}  // namespace skybake

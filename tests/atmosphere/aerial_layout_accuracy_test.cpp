// The aerial perspective's two slice layouts at the same 32 x 32 x 32
// froxels and range (docs/decisions/table-convention-key.md): skybake's
// linear slices, d_k = (k + 0.5) / n R, and Hillaire's squared slices,
// d_k = ((k + 0.5) / n)^2 R ("convention": "hillaire_demo", here with
// skybake's alpha for the comparison's sake: A compared as transmittance).
// Each layout's lookup is compared with a march of 400 segments to the same
// point, at points spread evenly over the screen and either evenly in
// distance or evenly in log distance (the near field, where squared slices
// crowd), 5 degrees and more above the horizon.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/hillaire_demo_lookups.hpp"
#include "core/error_stats.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

struct SliceError {
  double rms = 0.0, max = 0.0;  // worst of the RGB and A channels, relative
};

struct SliceComparison {
  SliceError linear, squared;
};

// Relative per channel, with a floor of 1e-3 of the channel's largest reference.
SliceError slice_error(const std::vector<glm::dvec4>& lut, const std::vector<glm::dvec4>& ref) {
  glm::dvec4 top(0.0), sum(0.0);
  for (const glm::dvec4& r : ref) top = glm::max(top, glm::abs(r));
  SliceError e;
  for (size_t i = 0; i < ref.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const double d = std::abs(lut[i][c] - ref[i][c]) / std::max(std::abs(ref[i][c]), 1e-3 * top[c]);
      sum[c] += d * d;
      e.max = std::max(e.max, d);
    }
  for (int c = 0; c < 4; ++c) e.rms = std::max(e.rms, std::sqrt(sum[c] / double(ref.size())));
  return e;
}

SliceComparison compare_slices(double range_m, bool log_distance, int points) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  AerialPerspectiveSpec spec;
  spec.depth_range_m = range_m;
  spec.camera.pitch_rad = 5.0 * kDeg;
  spec.sun_zenith_rad = 75.0 * kDeg;
  spec.sun_azimuth_rad = 20.0 * kDeg;
  const Texture linear =
      bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, spec, {});
  spec.convention = TableConvention::hillaire_demo;
  const Texture squared =
      bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, spec, {});
  const glm::dvec3 pos(0.0, 0.0, atm.bottom_radius_m + spec.camera.altitude_m);
  const glm::dvec3 sun = sun_direction(spec.sun_zenith_rad, spec.sun_azimuth_rad);
  std::vector<glm::dvec4> a, b, ref;
  for (int i = 0; i < points; ++i) {
    // The upper half of the screen, 5 degrees and more above the horizon:
    // no ground, where the two layouts' froxels differ by design.
    const glm::dvec2 uv(query_unit(size_t(i), 50), 0.5 * query_unit(size_t(i), 51));
    const double u = query_unit(size_t(i), 52);
    const double d = log_distance ? range_m * std::pow(1e-3, 1.0 - u) : range_m * u;
    const ScatteringResult r = integrate_scattered_luminance(
        atm, in.transmittance, &in.multiscattering, pos, view_dir_from_screen_uv(spec.camera, uv),
        sun, d, 400);
    ref.push_back(glm::dvec4(r.luminance, (r.transmittance.x + r.transmittance.y +
                                           r.transmittance.z) / 3.0));
    a.push_back(lookup_aerial_perspective(linear, range_m, uv, d));
    glm::dvec4 s = lookup_demo_aerial_perspective(squared, range_m, uv, d);
    // The demo's A is the opacity: compare transmittance with transmittance.
    s.w = 1.0 - s.w;
    b.push_back(s);
  }
  return {slice_error(a, ref), slice_error(b, ref)};
}

// In-scattering and opacity grow in proportion to the distance near the
// camera, which linear slices (and skybake's fade from the camera to the
// first slice) interpolate exactly, and squared slices, interpolated in
// sqrt(d), do not (up to 25 % between their first two slices). Over
// skybake's 32 km the linear slices read closer, near the camera and
// evenly; over his 128 km (4 km a linear slice, the first one 2 km out) the
// squared ones do.
TEST(AerialLayoutAccuracy, SquaredAgainstLinearSlices) {
  for (double range : {32e3, 128e3}) {
    for (bool log_distance : {false, true}) {
      const SliceComparison c = compare_slices(range, log_distance, 2048);
      std::printf(
          "aerial perspective over %3.0f km, %s distances: linear rms %.3g max %.3g | squared "
          "rms %.3g max %.3g\n",
          range * 1e-3, log_distance ? "log-even" : "even", c.linear.rms, c.linear.max,
          c.squared.rms, c.squared.max);
      if (range < 100e3) {
        EXPECT_LT(c.linear.rms, c.squared.rms) << range << " " << log_distance;
      } else {
        EXPECT_LT(c.squared.rms, c.linear.rms) << range << " " << log_distance;
      }
    }
  }
}

}  // namespace
}  // namespace skybake

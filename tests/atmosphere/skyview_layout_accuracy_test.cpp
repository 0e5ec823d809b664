// The sky-view's two azimuth layouts at the same 192 x 108 texels
// (docs/decisions/table-convention-key.md): skybake's full circle,
// u = phi / (2 pi), and Hillaire's half circle, u = sqrt(0.5 - 0.5 cos phi)
// with the sun at u = 0 ("convention": "hillaire_demo"). The sky is
// symmetric about the sun's vertical plane, so the half circle holds each
// azimuth once where the full circle holds it twice. Each layout's lookup
// is compared with the march of its own direction (the texels' own
// integrator, so only the table's interpolation differs) at directions
// spread evenly over the sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "atmosphere/hillaire_demo_lookups.hpp"
#include "core/error_stats.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

struct LayoutError {
  double rms = 0.0, max = 0.0;  // worst channel, relative
};

// Relative error per channel with a floor of 1e-3 of the view's brightest
// reference (the night side of a low sun is too faint to weigh).
LayoutError layout_error(const std::vector<glm::dvec3>& lut, const std::vector<glm::dvec3>& ref) {
  glm::dvec3 top(0.0), sum(0.0);
  for (const glm::dvec3& r : ref) top = glm::max(top, r);
  LayoutError e;
  for (size_t i = 0; i < ref.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(lut[i][c] - ref[i][c]) / std::max(ref[i][c], 1e-3 * top[c]);
      sum[c] += d * d;
      e.max = std::max(e.max, d);
    }
  for (int c = 0; c < 3; ++c) e.rms = std::max(e.rms, std::sqrt(sum[c] / double(ref.size())));
  return e;
}

struct LayoutComparison {
  LayoutError full, half;
};

// Views: altitude (m) and sun elevation (degrees); `directions` evenly spread.
LayoutComparison compare_layouts(double altitude_m, double sun_elevation_deg, int directions,
                                 int width, int height) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  SkyviewLutSpec spec;
  spec.width = width;
  spec.height = height;
  spec.views = {{altitude_m, (90.0 - sun_elevation_deg) * kDeg}};
  const Texture full = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  spec.convention = TableConvention::hillaire_demo;
  const Texture half = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  const double r = atm.bottom_radius_m + altitude_m;
  const double zs = spec.views[0].sun_zenith_rad;
  const glm::dvec3 sun(std::sin(zs), 0.0, std::cos(zs));
  std::vector<glm::dvec3> a, b, ref;
  for (int i = 0; i < directions; ++i) {
    // Hashed points (core/error_stats.hpp query_unit), uniform over the sphere.
    const double mu = 2.0 * query_unit(size_t(i), 40) - 1.0;
    const double phi = 2.0 * kPi * query_unit(size_t(i), 41);
    const SkyviewDirection d{mu, phi};
    ref.push_back(integrate_scattered_luminance(atm, in.transmittance, &in.multiscattering,
                                                {0, 0, r}, skyview_vector_from_direction(d), sun,
                                                INFINITY, spec.steps,
                                                {StepDistribution::quadratic, false})
                      .luminance);
    a.push_back(lookup_skyview(full, 0, atm, r, d));
    b.push_back(lookup_demo_skyview(half, 0, atm, r, d));
  }
  return {layout_error(a, ref), layout_error(b, ref)};
}

// At the default 192 x 108 the latitude's rows limit both layouts alike
// (measured: 0.13-0.16 % RMS either way); where the azimuth limits (48
// azimuth texels, or 432 rows) the half circle reads the sky closer to its
// march, by 3 to 9 times in RMS for a low sun.
TEST(SkyviewLayoutAccuracy, HalfCircleAgainstFullCircle) {
  for (glm::ivec2 size : {glm::ivec2(192, 108), glm::ivec2(48, 108), glm::ivec2(192, 432),
                          glm::ivec2(48, 432)}) {
    for (double alt : {200.0, 10e3}) {
      for (double sun : {60.0, 10.0, 2.0}) {
        const LayoutComparison c = compare_layouts(alt, sun, 4096, size.x, size.y);
        std::printf(
            "sky-view %dx%d, %5.0f m, sun %4.1f deg: full circle rms %.3g max %.3g | half "
            "circle rms %.3g max %.3g\n",
            size.x, size.y, alt, sun, c.full.rms, c.full.max, c.half.rms, c.half.max);
        if (size == glm::ivec2(192, 108)) {
          EXPECT_NEAR(c.half.rms, c.full.rms, 0.1 * c.full.rms) << alt << " m, sun " << sun;
        } else {
          EXPECT_LT(c.half.rms, c.full.rms) << size.x << "x" << size.y << " " << alt << " m, sun " << sun;
        }
      }
    }
  }
}

}  // namespace
}  // namespace skybake

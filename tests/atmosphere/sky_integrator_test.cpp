// Tests of the sky ray march (atmosphere/sky_integrator.hpp): the segment
// integral's closed form (a constant source, and a linear one between the
// segment's ends: segment_sources.hpp), clipping rays to the shell, an empty atmosphere,
// single scattering in a uniform slab against its closed form, the planet's
// shadow, the lit ground, viewers in space, the cumulative profile and stiff
// media.
#include "atmosphere/sky_integrator.hpp"

#include <cmath>
#include <cstring>
#include <functional>

#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/segment_sources.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/simd_targets.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using fixtures::earth_atmosphere;
using fixtures::empty_atmosphere;
using fixtures::uniform_slab_atmosphere;

const glm::dvec3 kUp(0.0, 0.0, 1.0);

bool all_finite(glm::dvec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Texture small_transmittance(const Atmosphere& atm) {
  return bake_transmittance_lut(atm, {128, 64, 40}, {});
}

TEST(IntegrateSegment, MatchesClosedFormAndLimits) {
  // integral_0^d S exp(-s t) dt = S (1 - exp(-s d)) / s.
  const glm::dvec3 s(2e-5, 1e-3, 0.0);
  const glm::dvec3 out = integrate_segment(glm::dvec3(3.0), s, 1500.0);
  EXPECT_NEAR(out.x, 3.0 * (1.0 - std::exp(-0.03)) / 2e-5, 1e-9);
  EXPECT_NEAR(out.y, 3.0 * (1.0 - std::exp(-1.5)) / 1e-3, 1e-9);
  EXPECT_DOUBLE_EQ(out.z, 3.0 * 1500.0);  // no extinction: S d
  // Optically thick: never more than S / sigma_t, however long the segment.
  const glm::dvec3 thick = integrate_segment(glm::dvec3(1.0), glm::dvec3(1.0), 1e9);
  EXPECT_DOUBLE_EQ(thick.x, 1.0);
  // Tiny optical depth keeps full precision (expm1): S d (1 - s d / 2).
  const glm::dvec3 thin = integrate_segment(glm::dvec3(1.0), glm::dvec3(1e-15), 1.0);
  EXPECT_NEAR(thin.x, 1.0, 1e-15);
}

TEST(EndSources, LinearSourceIntegralMatchesQuadrature) {
  // integral_0^dt exp(-sigma s) (a + (b - a) s / dt) ds by composite Simpson
  // (400000 intervals: (x / n)^4 / 180 < 1e-13 relative even at x = 750), on
  // both sides of the series' threshold and in thick and thin segments.
  const double dt = 100.0, a = 2.0, b = 5.0;
  for (double x : {0.0, 1e-7, 9.99e-4, 1.001e-3, 0.3, 10.0, 750.0}) {
    const double sigma = x / dt;
    const auto f = [&](double s) { return std::exp(-sigma * s) * (a + (b - a) * s / dt); };
    const int n = 400000;
    double sum = f(0.0) + f(dt);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(dt * k / n);
    const double quadrature = sum * dt / n / 3.0;
    const EndSourceWeights w = end_source_weights(x, std::expm1(-x), dt);
    EXPECT_NEAR(end_source_integral(a, b, w), quadrature, 1e-12 * quadrature) << x;
    // A constant source: the energy-conserving weight of segment_weights.
    EXPECT_NEAR(w.weight, segment_weights(glm::dvec3(sigma), dt).weight.x, 1e-14 * w.weight) << x;
  }
}

TEST(ClipRay, GroundViewerZenithAndNadir) {
  const Atmosphere atm = earth_atmosphere();
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m);
  const AtmosphereSpan up = clip_ray_to_atmosphere(atm, p, kUp);
  EXPECT_TRUE(up.hits_atmosphere);
  EXPECT_FALSE(up.exits_on_ground);
  EXPECT_DOUBLE_EQ(up.t_enter, 0.0);
  EXPECT_NEAR(up.t_exit, atm.top_radius_m - atm.bottom_radius_m, 1e-6);
  const AtmosphereSpan down = clip_ray_to_atmosphere(atm, p, -kUp);
  EXPECT_TRUE(down.exits_on_ground);
  EXPECT_DOUBLE_EQ(down.t_exit, 0.0);
}

TEST(ClipRay, SpaceViewerEntersAtTheTopOrMisses) {
  const Atmosphere atm = earth_atmosphere();
  const double r = 2.0 * atm.top_radius_m;
  const glm::dvec3 p(0.0, 0.0, r);
  const AtmosphereSpan down = clip_ray_to_atmosphere(atm, p, -kUp);
  EXPECT_TRUE(down.hits_atmosphere);
  EXPECT_NEAR(down.t_enter, r - atm.top_radius_m, 1e-6);
  EXPECT_NEAR(down.t_exit, r - atm.bottom_radius_m, 1e-6);
  EXPECT_TRUE(down.exits_on_ground);
  EXPECT_FALSE(clip_ray_to_atmosphere(atm, p, kUp).hits_atmosphere);
  EXPECT_FALSE(clip_ray_to_atmosphere(atm, p, {1.0, 0.0, 0.0}).hits_atmosphere);
  // A grazing ray past the planet through the shell: enters and leaves at the top.
  const glm::dvec3 side(-1.0, 0.0, 0.0);
  const glm::dvec3 q(atm.top_radius_m, 0.0, 0.5 * (atm.top_radius_m + atm.bottom_radius_m));
  const AtmosphereSpan graze = clip_ray_to_atmosphere(atm, q, side);
  EXPECT_TRUE(graze.hits_atmosphere);
  EXPECT_FALSE(graze.exits_on_ground);
  EXPECT_GT(graze.t_exit, graze.t_enter);
}

TEST(Integrator, EmptyAtmosphereIsBlackAndClear) {
  const Atmosphere atm = empty_atmosphere();
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 100.0);
  for (const glm::dvec3 dir : {kUp, glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(1, 0, -1))}) {
    const ScatteringResult s =
        integrate_scattered_luminance(atm, t, nullptr, p, dir, kUp, INFINITY, 30);
    EXPECT_EQ(s.luminance, glm::dvec3(0.0));
    EXPECT_EQ(s.transmittance, glm::dvec3(1.0));
  }
}

TEST(Integrator, UniformSlabZenithMatchesSingleScatteringClosedForm) {
  // Sun and view at the zenith, constant sigma_s (no absorption) over height
  // H: T(viewer, x) T_sun(x) = exp(-sigma t) exp(-sigma (H - t)) = exp(-sigma H)
  // for every x, so L = E p(1) sigma H exp(-sigma H) and T = exp(-sigma H).
  const glm::dvec3 sigma(2e-6, 1e-5, 3e-5);
  const Atmosphere atm = uniform_slab_atmosphere(sigma, glm::dvec3(0.0));
  const double height = atm.top_radius_m - atm.bottom_radius_m;
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m);
  const ScatteringResult s =
      integrate_scattered_luminance(atm, t, nullptr, p, kUp, kUp, INFINITY, 64);
  for (int c = 0; c < 3; ++c) {
    const double expected = rayleigh_phase(1.0) * sigma[c] * height * std::exp(-sigma[c] * height);
    EXPECT_NEAR(s.luminance[c], expected, 2e-3 * expected) << c;
    // Constant extinction: the segment products are exact.
    EXPECT_NEAR(s.transmittance[c], std::exp(-sigma[c] * height), 1e-12) << c;
  }
}

TEST(Integrator, SunAtNadirLeavesTheZenithRayInTheShadow) {
  // Every point of the zenith ray sees the sun through the planet: Vis = 0.
  // The multiple-scattering LUT is black there too (everything it integrates
  // is in the shadow and the ground is unlit), so the result is exactly 0.
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const Texture ms = bake_multiscattering_lut(atm, t, {8, 8, 16, 10}, {});
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m);
  const ScatteringResult s = integrate_scattered_luminance(atm, t, &ms, p, kUp, -kUp, INFINITY, 30);
  EXPECT_EQ(s.luminance, glm::dvec3(0.0));
  EXPECT_LT(s.transmittance.z, 1.0);
}

TEST(Integrator, ShadowCutsOnlyWhereTheRayCrossesTheShadow) {
  // Sun at the zenith: no point of the shell is in the shadow, so the cut
  // march is the plain march bit for bit. Sun below the horizon: a ray
  // toward the sun's side leaves the shadow on its way: a segment straddling
  // the shadow's edge is off by O(h), so the cut march converges faster
  // (second order) and its extrapolation beats the plain march at more
  // steps.
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 1e3);
  IntegrationOptions cut;
  cut.cut_at_shadow = true;
  for (double elevation : {-0.2, 0.05, 0.6}) {
    const glm::dvec3 dir =
        glm::normalize(glm::dvec3(std::cos(elevation), 0.0, std::sin(elevation)));
    EXPECT_EQ(
        integrate_scattered_luminance(atm, t, nullptr, p, dir, kUp, INFINITY, 37, cut).luminance,
        integrate_scattered_luminance(atm, t, nullptr, p, dir, kUp, INFINITY, 37).luminance);
  }
  // Rays toward the sun's side from a viewer 1 km up, the sun 3-11 degrees
  // below the horizon: rms over the rays and channels of the relative
  // error against 4000 cut steps.
  const auto rms_error = [&](const std::function<glm::dvec3(glm::dvec3, glm::dvec3)>& march) {
    double sum = 0.0;
    int count = 0;
    for (double below : {0.05, 0.1, 0.2})
      for (double elevation : {0.01, 0.03, 0.06, 0.1, 0.15, 0.2, 0.3}) {
        const glm::dvec3 sun(std::cos(below), 0.0, -std::sin(below));
        const glm::dvec3 dir =
            glm::normalize(glm::dvec3(std::cos(elevation), 0.3, std::sin(elevation)));
        const glm::dvec3 dense =
            integrate_scattered_luminance(atm, t, nullptr, p, dir, sun, INFINITY, 4000, cut)
                .luminance;
        const glm::dvec3 value = march(dir, sun);
        for (int c = 0; c < 3; ++c, ++count) sum += std::pow(value[c] / dense[c] - 1.0, 2);
      }
    return std::sqrt(sum / count);
  };
  const auto plain = [&](int n) {
    return rms_error([&](glm::dvec3 dir, glm::dvec3 sun) {
      return integrate_scattered_luminance(atm, t, nullptr, p, dir, sun, INFINITY, n).luminance;
    });
  };
  const auto cut_march = [&](int n) {
    return rms_error([&](glm::dvec3 dir, glm::dvec3 sun) {
      return integrate_scattered_luminance(atm, t, nullptr, p, dir, sun, INFINITY, n, cut)
          .luminance;
    });
  };
  const double extrapolated = rms_error([&](glm::dvec3 dir, glm::dvec3 sun) {
    return extrapolated_scattered_luminance(atm, t, nullptr, p, dir, sun, INFINITY, 50);
  });
  // Measured: plain 1.36e-3 at 100 steps, 5.1e-4 at 200; cut 7.5e-4 and
  // 2.2e-4 (second order); extrapolated from 100 and 50, 3.3e-4.
  EXPECT_GT(cut_march(100) / cut_march(200), 3.0);
  EXPECT_LT(cut_march(200), 0.6 * plain(200));
  EXPECT_LT(extrapolated, plain(200));
}

TEST(Integrator, BlockExponentialsAreTheMarchToRounding) {
  // The references' block exponentials (IntegrationOptions::
  // block_exponentials) against libm's per segment: the same march within
  // rounding, on Earth with its multiple-scattering table and the tiny
  // planet's stiff sky, lit and shadowed rays, cut and plain, both step
  // distributions, viewers on the ground and in space.
  for (const Atmosphere& atm : {earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb + 0.01 * (rt - rb), rb + 0.5 * (rt - rb), 1.5 * rt})
      for (double elevation : {-0.9, -0.05, 0.02, 0.4, 1.4})
        for (double sun_elevation : {-0.1, 0.05, 0.8})
          for (bool cut : {false, true}) {
            IntegrationOptions options;
            options.cut_at_shadow = cut;
            options.distribution = cut ? StepDistribution::quadratic : StepDistribution::uniform;
            options.lit_ground = true;
            const glm::dvec3 p(0.0, 0.0, r);
            const glm::dvec3 dir(std::cos(elevation), 0.0, std::sin(elevation));
            const glm::dvec3 sun(std::cos(sun_elevation) * 0.6, std::cos(sun_elevation) * 0.8,
                                 std::sin(sun_elevation));
            const ScatteringResult one = integrate_scattered_luminance(
                atm, l.transmittance, &l.multiscattering, p, dir, sun, INFINITY, 41, options);
            options.block_exponentials = true;
            const ScatteringResult block = integrate_scattered_luminance(
                atm, l.transmittance, &l.multiscattering, p, dir, sun, INFINITY, 41, options);
            for (int c = 0; c < 3; ++c) {
              ASSERT_NEAR(block.luminance[c], one.luminance[c], 1e-13 * one.luminance[c])
                  << r << " " << elevation << " " << sun_elevation << " " << cut;
              ASSERT_NEAR(block.transmittance[c], one.transmittance[c],
                          1e-13 * one.transmittance[c] + 1e-300);
            }
          }
  }
}

// The block march with and without IntegrationOptions::finite_tables over
// lit and shadowed rays, both source rules, cut and plain: the luminance and
// transmittance bits of each pair compared.
void expect_dark_reads_left_out_keep_bits(const Atmosphere& atm, const Texture& transmittance,
                                          const Texture& multiscattering) {
  const CachedFiniteCheck finite{&transmittance, &multiscattering};
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  for (double r : {rb + 10.0, rb + 0.5 * (rt - rb), 1.5 * rt})
    for (double elevation : {-0.9, -0.05, 0.02, 0.4, 1.4})
      for (double sun_elevation : {-1.2, -0.1, 0.05, 0.8})
        for (int rule = 0; rule < 4; ++rule) {
          IntegrationOptions options;
          options.block_exponentials = true;
          options.sources_at_ends = rule >= 2;
          options.cut_at_shadow = rule % 2 == 1;
          const glm::dvec3 p(0.0, 0.0, r);
          const glm::dvec3 dir(std::cos(elevation), 0.0, std::sin(elevation));
          const glm::dvec3 sun(std::cos(sun_elevation) * 0.6, std::cos(sun_elevation) * 0.8,
                               std::sin(sun_elevation));
          const ScatteringResult all = integrate_scattered_luminance(
              atm, transmittance, &multiscattering, p, dir, sun, INFINITY, 41, options);
          options.finite_tables = &finite;
          const ScatteringResult fast = integrate_scattered_luminance(
              atm, transmittance, &multiscattering, p, dir, sun, INFINITY, 41, options);
          EXPECT_EQ(std::memcmp(&all.luminance, &fast.luminance, sizeof all.luminance), 0)
              << r << " " << elevation << " " << sun_elevation << " " << rule;
          EXPECT_EQ(std::memcmp(&all.transmittance, &fast.transmittance, sizeof all.transmittance),
                    0)
              << r << " " << elevation << " " << sun_elevation << " " << rule;
        }
}

TEST(Integrator, DarkReadsLeftOutKeepEveryBit) {
  // The references leave out the reads past the point where the view ray's
  // transmittance underflows to 0, along rays that scatter nothing, and of
  // groups wholly in the planet's shadow: the same bits as reading them, on
  // every SIMD target. Earth, Earth under Rayleigh of 1 /m (opaque within
  // metres), and Earth's air with scattering turned to absorption.
  Atmosphere opaque = earth_atmosphere();
  for (MediumComponent& c : opaque.components)
    if (c.name == "rayleigh") c.scattering_per_m = glm::dvec3(1.0);
  Atmosphere absorber = earth_atmosphere();
  for (MediumComponent& c : absorber.components) {
    c.absorption_per_m += c.scattering_per_m;
    c.scattering_per_m = glm::dvec3(0.0);
  }
  for (const Atmosphere& atm : {earth_atmosphere(), opaque, absorber}) {
    const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
      const test::SimdTargetAs as(target);
      expect_dark_reads_left_out_keep_bits(atm, l.transmittance, l.multiscattering);
    }
  }
  // A table with an infinite texel: nothing is left out (0 times it is NaN).
  fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(opaque);
  l.multiscattering.data[5] = INFINITY;
  expect_dark_reads_left_out_keep_bits(opaque, l.transmittance, l.multiscattering);
}

TEST(Integrator, MappingParsedOnceIsTheMappingParsedPerRay) {
  // A caller's parsed multiple-scattering mapping (IntegrationOptions::
  // multiscattering_mapping) gives the march's bits; a wrong one would not.
  const Atmosphere atm = earth_atmosphere();
  const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
  const MultiscatteringMapping parsed = multiscattering_mapping_of(l.multiscattering);
  MultiscatteringMapping wrong = parsed;
  wrong.altitude = parsed.altitude == AltitudeMapping::linear ? AltitudeMapping::quadratic
                                                              : AltitudeMapping::linear;
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 500.0), dir(0.8, 0.0, 0.6);
  const glm::dvec3 sun(0.6, 0.0, 0.8);
  const auto march = [&](const MultiscatteringMapping* mapping) {
    IntegrationOptions options;
    options.multiscattering_mapping = mapping;
    return integrate_scattered_luminance(atm, l.transmittance, &l.multiscattering, p, dir, sun,
                                         INFINITY, 40, options)
        .luminance;
  };
  EXPECT_EQ(march(&parsed), march(nullptr));
  EXPECT_NE(march(&wrong), march(nullptr));
}

TEST(Integrator, LitGroundSeenThroughEmptyAtmosphereIsLambertian) {
  // No medium: looking straight down from 1 km sees albedo / pi * E * mu_s.
  Atmosphere atm = empty_atmosphere();
  atm.ground_albedo = glm::dvec3(0.2, 0.3, 0.4);
  atm.sun_illuminance = glm::dvec3(2.0);
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 1e3);
  const double mu_s = 0.6;
  const glm::dvec3 sun(std::sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const ScatteringResult s = integrate_scattered_luminance(atm, t, nullptr, p, -kUp, sun, INFINITY,
                                                           8, {StepDistribution::uniform, true});
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(s.luminance[c], atm.ground_albedo[c] / kPi * 2.0 * mu_s, 1e-12) << c;
  // Without the option the ground is not added.
  const ScatteringResult off =
      integrate_scattered_luminance(atm, t, nullptr, p, -kUp, sun, INFINITY, 8);
  EXPECT_EQ(off.luminance, glm::dvec3(0.0));
}

TEST(Integrator, SpaceViewerEqualsViewerMovedToTheTop) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, 0.0, -1.0));
  const glm::dvec3 sun = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
  const glm::dvec3 far = glm::dvec3(0.0, 0.0, 3.0 * atm.top_radius_m);
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, far, dir);
  ASSERT_TRUE(span.hits_atmosphere);
  const glm::dvec3 entry = far + span.t_enter * dir;
  const ScatteringResult a =
      integrate_scattered_luminance(atm, t, nullptr, far, dir, sun, INFINITY, 40);
  const ScatteringResult b =
      integrate_scattered_luminance(atm, t, nullptr, entry, dir, sun, INFINITY, 40);
  ASSERT_GT(b.luminance.z, 0.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(a.luminance[c], b.luminance[c], 1e-6 * b.luminance[c]) << c;
    EXPECT_NEAR(a.transmittance[c], b.transmittance[c], 1e-9) << c;
  }
  // A ray that misses the shell: nothing.
  const ScatteringResult miss =
      integrate_scattered_luminance(atm, t, nullptr, far, kUp, sun, INFINITY, 40);
  EXPECT_EQ(miss.luminance, glm::dvec3(0.0));
  EXPECT_EQ(miss.transmittance, glm::dvec3(1.0));
}

TEST(Integrator, ProfileIsMonotonicAndEndsOnTheDirectMarch) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 200.0);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 0.0, 0.05));
  const glm::dvec3 sun = glm::normalize(glm::dvec3(1.0, 0.5, 0.4));
  std::vector<double> d;
  for (int k = 0; k < 16; ++k) d.push_back((k + 0.5) * 2e3);
  const std::vector<ScatteringResult> prof =
      integrate_scattered_luminance_profile(atm, t, nullptr, p, dir, sun, d, 3);
  for (size_t k = 1; k < prof.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(prof[k].luminance[c], prof[k - 1].luminance[c]) << k;
      EXPECT_LT(prof[k].transmittance[c], prof[k - 1].transmittance[c]) << k;
    }
  }
  // Zero distance: nothing scattered, nothing absorbed.
  const ScatteringResult zero = integrate_scattered_luminance(atm, t, nullptr, p, dir, sun, 0.0, 7);
  EXPECT_EQ(zero.luminance, glm::dvec3(0.0));
  EXPECT_EQ(zero.transmittance, glm::dvec3(1.0));
  // One interval of n segments is the plain uniform march of n segments.
  const std::vector<ScatteringResult> one =
      integrate_scattered_luminance_profile(atm, t, nullptr, p, dir, sun, {5e3}, 7);
  const ScatteringResult direct =
      integrate_scattered_luminance(atm, t, nullptr, p, dir, sun, 5e3, 7);
  EXPECT_EQ(one[0].luminance, direct.luminance);
  EXPECT_EQ(one[0].transmittance, direct.transmittance);
}

TEST(Integrator, ProfileStopsAtTheGround) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 100.0);
  const glm::dvec3 down = glm::normalize(glm::dvec3(1.0, 0.0, -1.0));  // ground at ~141 m
  const std::vector<ScatteringResult> prof =
      integrate_scattered_luminance_profile(atm, t, nullptr, p, down, kUp, {50.0, 1e3, 5e3}, 2);
  EXPECT_GT(prof[1].luminance.z, prof[0].luminance.z);
  EXPECT_EQ(prof[1].luminance, prof[2].luminance);
  EXPECT_EQ(prof[1].transmittance, prof[2].transmittance);
}

// Stiff media (presets/extreme/): finite, non-negative, transmittance in [0, 1].
void expect_sane_everywhere(const Atmosphere& atm) {
  const Texture t = small_transmittance(atm);
  const Texture ms = bake_multiscattering_lut(atm, t, {8, 8, 16, 10}, {});
  const double top = atm.top_radius_m, bottom = atm.bottom_radius_m;
  for (double r : {bottom, bottom + 0.01 * (top - bottom), top, 1.5 * top}) {
    for (double mu_v : {1.0, 0.3, 0.0, -1e-9, -0.2, -1.0}) {
      for (double mu_s : {1.0, 0.05, 0.0, -0.1, -1.0}) {
        const glm::dvec3 dir(std::sqrt(1.0 - mu_v * mu_v), 0.0, mu_v);
        const glm::dvec3 sun(std::sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
        const ScatteringResult s =
            integrate_scattered_luminance(atm, t, &ms, {0.0, 0.0, r}, dir, sun, INFINITY, 30,
                                          {StepDistribution::quadratic, true});
        ASSERT_TRUE(all_finite(s.luminance)) << r << " " << mu_v << " " << mu_s;
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(s.luminance[c], 0.0);
          EXPECT_GE(s.transmittance[c], 0.0);
          EXPECT_LE(s.transmittance[c], 1.0);
        }
      }
    }
  }
}

TEST(Integrator, StiffMediaStayFinite) {
  Atmosphere dense = earth_atmosphere();
  dense.components[0].scattering_per_m *= 100.0;
  expect_sane_everywhere(dense);
  Atmosphere sharp = earth_atmosphere();
  sharp.components[1].g = 0.999;
  expect_sane_everywhere(sharp);
  Atmosphere tiny = earth_atmosphere();  // a 1 km planet under a 100 km atmosphere
  tiny.bottom_radius_m = 1e3;
  tiny.top_radius_m = 101e3;
  expect_sane_everywhere(tiny);
}

TEST(Integrator, BlockMarchHasTheSameBitsOnEverySimdTarget) {
  // The references' march (block exponentials, the sources read at the
  // midpoints or at the ends) on each SIMD target against the scalar one:
  // ground and space viewers, lit and shadowed, cut at the shadow and plain.
  Atmosphere dense = fixtures::earth_atmosphere();
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense}) {
    const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb + 0.01 * (rt - rb), rb + 0.5 * (rt - rb), 1.5 * rt})
      for (double elevation : {-0.9, -0.05, 0.02, 0.4, 1.4})
        for (double sun_elevation : {-0.1, 0.05, 0.8})
          for (bool at_ends : {false, true}) {
            IntegrationOptions options;
            options.cut_at_shadow = !at_ends;
            options.distribution = at_ends ? StepDistribution::uniform : StepDistribution::quadratic;
            options.block_exponentials = true;
            options.sources_at_ends = at_ends;
            options.lit_ground = true;
            const glm::dvec3 p(0.0, 0.0, r);
            const glm::dvec3 dir(std::cos(elevation), 0.0, std::sin(elevation));
            const glm::dvec3 sun(std::cos(sun_elevation) * 0.6, std::cos(sun_elevation) * 0.8,
                                 std::sin(sun_elevation));
            const auto march = [&](int64_t target) {
              const test::SimdTargetAs as(target);
              return integrate_scattered_luminance(atm, l.transmittance, &l.multiscattering, p,
                                                   dir, sun, INFINITY, 41, options);
            };
            const ScatteringResult one = march(HWY_SCALAR);
            for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
              const ScatteringResult wide = march(target);
              ASSERT_EQ(wide.luminance, one.luminance)
                  << r << " " << elevation << " " << at_ends << " " << hwy::TargetName(target);
              ASSERT_EQ(wide.transmittance, one.transmittance);
            }
          }
  }
}

}  // namespace
}  // namespace skybake

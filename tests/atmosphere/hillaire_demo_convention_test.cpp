// Tables baked in the "hillaire_demo" convention (atmosphere/table_convention.hpp)
// read by an independent transcription of the run-time reads of Hillaire's
// demo (tests/support/hillaire_demo_reads.hpp): at the points his reads
// take texel centres, the value is the one skybake computes at that physical
// point (r, mu, mu_s, view direction, froxel); anywhere, his read agrees
// with skybake's own lookup of the convention (hillaire_demo_lookups.hpp).
// Bar: 1e-4 relative; float storage alone leaves ~1e-7.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/hillaire_demo_lookups.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/table_convention.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/hillaire_demo_reads.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using fixtures::earth_atmosphere;
namespace demo = demo_reads;

constexpr double kBar = 1e-4;

// Largest relative difference over the channels, with an absolute floor
// (luminance far below the table's values is compared absolutely).
double rel_diff(glm::dvec4 a, glm::dvec4 b, int channels, double floor) {
  double worst = 0.0;
  for (int c = 0; c < channels; ++c)
    worst = std::max(worst, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), floor));
  return worst;
}

TEST(DemoConvention, PlacementsInvertTheirReads) {
  for (int n : {2, 32, 108, 192}) {
    for (int i = 0; i < n; ++i) {
      const double centre = texel_center(i, n);
      EXPECT_NEAR(texture_coord_of_unit(TexelPlacement::sub_uv,
                                        unit_of_texel(TexelPlacement::sub_uv, i, n), n),
                  centre, 1e-15);
      EXPECT_NEAR(texture_coord_of_unit(TexelPlacement::centres,
                                        unit_of_texel(TexelPlacement::centres, i, n), n),
                  centre, 1e-15);
      EXPECT_EQ(skybake_coord_of_texel(TexelPlacement::ends, i, n), centre);
      // His reader's placement stays inside [0, 1].
      EXPECT_GE(unit_of_texel(TexelPlacement::sub_uv, i, n), 0.0);
      EXPECT_LE(unit_of_texel(TexelPlacement::sub_uv, i, n), 1.0);
    }
  }
  EXPECT_NEAR(demo_skyview_unit_from_cos_azimuth(1.0), 0.0, 1e-15);  // the sun at u = 0
  EXPECT_NEAR(demo_skyview_unit_from_cos_azimuth(-1.0), 1.0, 1e-15);
  EXPECT_NEAR(demo_aerial_slice_distance(31, 32, 128e3), demo::aerial_slice_distance(31, 4e3),
              1e-9);
}

TEST(DemoTransmittance, HisReadAtHisTexelCentresIsTheTransmittanceThere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  TransmittanceLutSpec spec{64, 16, 6};
  spec.convention = TableConvention::hillaire_demo;
  const Texture lut = bake_transmittance_lut(atm, spec, {});
  EXPECT_EQ(table_convention_of(lut), TableConvention::hillaire_demo);
  TransmittanceLutSpec ours{64, 16, 6};
  const Texture skybake_lut = bake_transmittance_lut(atm, ours, {});
  double worst = 0.0, worst_ours = 0.0;
  for (int j = 0; j < lut.height; ++j) {
    for (int i = 0; i < lut.width; ++i) {
      const glm::dvec2 p =
          demo::transmittance_params(rb, rt, {texel_center(i, 64), texel_center(j, 16)});
      const glm::dvec2 uv = demo::transmittance_uv(rb, rt, p.x, p.y);
      const glm::dvec3 exact = compute_transmittance_to_top(atm, p.x, p.y, 6, SegmentRule::gauss8);
      const glm::dvec4 ref(exact, 0.0);
      worst = std::max(worst, rel_diff(demo::sample_clamp(lut, uv.x, uv.y), ref, 3, 1e-30));
      worst_ours =
          std::max(worst_ours, rel_diff(demo::sample_clamp(skybake_lut, uv.x, uv.y), ref, 3, 1e-30));
    }
  }
  std::printf("transmittance: his read at his texel centres, worst %.3g (skybake's layout %.3g)\n",
              worst, worst_ours);
  EXPECT_LT(worst, kBar);
  // The test can fail: skybake's own layout, read his way, is half a texel off.
  EXPECT_GT(worst_ours, 100 * kBar);
}

TEST(DemoTransmittance, HisReadIsSkybakesLookupEverywhere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  TransmittanceLutSpec spec{64, 16, 6};
  spec.convention = TableConvention::hillaire_demo;
  const Texture lut = bake_transmittance_lut(atm, spec, {});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double r = rb + (rt - rb) * unit(rng) * unit(rng);
    const double mu_h = -std::sqrt(std::max(0.0, 1.0 - rb * rb / (r * r)));
    const double mu = mu_h + (1.0 - mu_h) * unit(rng);
    const glm::dvec2 uv = demo::transmittance_uv(rb, rt, r, mu);
    const glm::dvec4 his = demo::sample_clamp(lut, uv.x, uv.y);
    const glm::dvec4 ours(lookup_demo_transmittance_to_top(lut, atm, r, mu), 0.0);
    worst = std::max(worst, rel_diff(his, ours, 3, 1e-30));
  }
  std::printf("transmittance: his read against skybake's lookup, worst %.3g\n", worst);
  EXPECT_LT(worst, kBar);
}

TEST(DemoMultiscattering, HisReadAtHisTexelCentresIsPsiMsThere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  MultiscatteringLutSpec spec{16, 16, 32, 20};
  spec.convention = TableConvention::hillaire_demo;
  const Texture lut = bake_multiscattering_lut(atm, in.transmittance, spec, {});
  EXPECT_EQ(table_convention_of(lut), TableConvention::hillaire_demo);
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(32);
  double worst = 0.0, worst_ours = 0.0;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      // The point his GetMultipleScattering reads at texel (i, j)'s centre.
      const double mu_s = 2.0 * demo::unit_at_sub_uv(texel_center(i, 16), 16) - 1.0;
      const double r = rb + demo::unit_at_sub_uv(texel_center(j, 16), 16) * (rt - rb);
      const glm::dvec2 uv = demo::multiscattering_uv(rb, rt, r, mu_s, 16);
      const glm::dvec4 ref(compute_multiscattering(atm, in.transmittance, r, mu_s, dirs, 20).psi_ms,
                           0.0);
      worst = std::max(worst, rel_diff(demo::sample_clamp(lut, uv.x, uv.y), ref, 3, 1e-12));
      worst_ours = std::max(
          worst_ours, rel_diff(demo::sample_clamp(in.multiscattering, uv.x, uv.y), ref, 3, 1e-12));
    }
  }
  std::printf("multiscattering: his read at his texel centres, worst %.3g (skybake's layout %.3g)\n",
              worst, worst_ours);
  EXPECT_LT(worst, kBar);
}

TEST(DemoMultiscattering, HisReadIsSkybakesLookupEverywhere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  MultiscatteringLutSpec spec{16, 16, 32, 20};
  spec.convention = TableConvention::hillaire_demo;
  const Texture lut = bake_multiscattering_lut(atm, in.transmittance, spec, {});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double r = rb + (rt - rb) * unit(rng);
    const double mu_s = 2.0 * unit(rng) - 1.0;
    const glm::dvec2 uv = demo::multiscattering_uv(rb, rt, r, mu_s, 16);
    const glm::dvec4 ours(lookup_demo_multiscattering(lut, atm, r, mu_s), 0.0);
    worst = std::max(worst, rel_diff(demo::sample_clamp(lut, uv.x, uv.y), ours, 3, 1e-12));
  }
  std::printf("multiscattering: his read against skybake's lookup, worst %.3g\n", worst);
  EXPECT_LT(worst, kBar);
}

// A local-frame view vector from his (cos zenith, cos light-view azimuth).
glm::dvec3 view_vector(double cos_zenith, double cos_azimuth) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cos_zenith * cos_zenith));
  return {s * cos_azimuth, s * std::sqrt(std::max(0.0, 1.0 - cos_azimuth * cos_azimuth)),
          cos_zenith};
}

SkyviewLutSpec demo_skyview_spec() {
  SkyviewLutSpec spec;
  spec.views = {{200.0, 60.0 * kDeg}, {10e3, 88.0 * kDeg}};
  spec.convention = TableConvention::hillaire_demo;
  return spec;
}

TEST(DemoSkyview, HisReadAtHisTexelCentresIsTheMarchThere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m;
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  const SkyviewLutSpec spec = demo_skyview_spec();
  const Texture sky = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  ASSERT_EQ(sky.width, 192);
  ASSERT_EQ(sky.height, 108);
  double worst = 0.0;
  for (int layer = 0; layer < 2; ++layer) {
    const double r = rb + spec.views[layer].altitude_m;
    const double zs = spec.views[layer].sun_zenith_rad;
    const glm::dvec3 sun(std::sin(zs), 0.0, std::cos(zs));
    for (int y = 0; y < 108; y += 3) {
      for (int x = 0; x < 192; x += 5) {
        const glm::dvec2 p = demo::skyview_params(rb, r, {texel_center(x, 192), texel_center(y, 108)});
        const glm::dvec3 dir = view_vector(p.x, p.y);
        const bool ground = ray_intersects_ground(rb, r, p.x);
        const glm::dvec2 uv = demo::skyview_uv(rb, r, ground, p.x, p.y);
        const ScatteringResult ref =
            integrate_scattered_luminance(atm, in.transmittance, &in.multiscattering, {0, 0, r},
                                          dir, sun, INFINITY, spec.steps,
                                          {StepDistribution::quadratic, false});
        worst = std::max(worst, rel_diff(demo::sample_clamp(sky, uv.x, uv.y, layer),
                                         glm::dvec4(ref.luminance, 0.0), 3, 1e-9));
      }
    }
  }
  std::printf("sky-view: his read at his texel centres, worst %.3g\n", worst);
  EXPECT_LT(worst, kBar);
}

TEST(DemoSkyview, HisReadIsSkybakesLookupEverywhere) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m;
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  const SkyviewLutSpec spec = demo_skyview_spec();
  const Texture sky = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int layer = 0; layer < 2; ++layer) {
    const double r = rb + spec.views[layer].altitude_m;
    const double mu_h = -std::sqrt(1.0 - rb * rb / (r * r));
    for (int k = 0; k < 3000; ++k) {
      const double mu = 2.0 * unit(rng) - 1.0;
      if (std::abs(mu - mu_h) < 1e-6) continue;  // his branch and ours split at the horizon
      const double phi = 2.0 * kPi * unit(rng);
      const glm::dvec2 uv =
          demo::skyview_uv(rb, r, ray_intersects_ground(rb, r, mu), mu, std::cos(phi));
      const glm::dvec4 his = demo::sample_clamp(sky, uv.x, uv.y, layer);
      const glm::dvec4 ours(lookup_demo_skyview(sky, layer, atm, r, {mu, phi}), 0.0);
      worst = std::max(worst, rel_diff(his, ours, 3, 1e-9));
    }
  }
  std::printf("sky-view: his read against skybake's lookup, worst %.3g\n", worst);
  EXPECT_LT(worst, kBar);
}

// The cut-down twin of skyview_layout_accuracy_test.cpp: where the azimuth
// limits (48 x 108, a ground viewer, the sun 2 degrees up), the half circle
// reads the sky at least twice as close to its march as the full circle.
TEST(DemoSkyview, HalfCircleBeatsFullCircleWhereTheAzimuthLimits) {
  const Atmosphere atm = earth_atmosphere();
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  SkyviewLutSpec spec;
  spec.width = 48;
  spec.views = {{200.0, 88.0 * kDeg}};
  const Texture full = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  spec.convention = TableConvention::hillaire_demo;
  const Texture half = bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, {});
  const double r = atm.bottom_radius_m + 200.0, zs = 88.0 * kDeg;
  const glm::dvec3 sun(std::sin(zs), 0.0, std::cos(zs));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double full_sq = 0.0, half_sq = 0.0;
  for (int k = 0; k < 512; ++k) {
    const SkyviewDirection d{0.9 * unit(rng), 2.0 * kPi * unit(rng)};  // the sky around the sun
    const glm::dvec3 ref = integrate_scattered_luminance(
        atm, in.transmittance, &in.multiscattering, {0, 0, r}, skyview_vector_from_direction(d),
        sun, INFINITY, spec.steps, {StepDistribution::quadratic, false}).luminance;
    const glm::dvec3 a = lookup_skyview(full, 0, atm, r, d) / ref - 1.0;
    const glm::dvec3 b = lookup_demo_skyview(half, 0, atm, r, d) / ref - 1.0;
    full_sq += glm::dot(a, a);
    half_sq += glm::dot(b, b);
  }
  std::printf("sky-view 48x108, sun 2 deg up: RMS full circle %.3g, half circle %.3g\n",
              std::sqrt(full_sq / 1536), std::sqrt(half_sq / 1536));
  EXPECT_LT(4.0 * half_sq, full_sq);  // RMS at most half
}

AerialPerspectiveSpec demo_aerial_spec() {
  AerialPerspectiveSpec spec;
  spec.depth_range_m = 128e3;
  spec.camera.pitch_rad = -10.0 * kDeg;  // the lower froxels reach the ground
  spec.sun_zenith_rad = 70.0 * kDeg;
  spec.sun_azimuth_rad = 30.0 * kDeg;
  spec.convention = TableConvention::hillaire_demo;
  return spec;
}

TEST(DemoAerialPerspective, HisFroxelsHoldTheirPathsWithOpacity) {
  const Atmosphere atm = earth_atmosphere();
  const double rb = atm.bottom_radius_m;
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  const AerialPerspectiveSpec spec = demo_aerial_spec();
  const Texture ap =
      bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, spec, {});
  const glm::dvec3 cam(0.0, 0.0, rb + spec.camera.altitude_m);
  const glm::dvec3 sun = sun_direction(spec.sun_zenith_rad, spec.sun_azimuth_rad);
  std::vector<double> distances(32);
  for (int k = 0; k < 32; ++k) distances[k] = demo::aerial_slice_distance(k, 4e3);
  double worst = 0.0;
  int moved = 0;
  for (int y = 0; y < 32; y += 3) {
    for (int x = 0; x < 32; x += 7) {
      const glm::dvec2 uv(texel_center(x, 32), texel_center(y, 32));
      const glm::dvec3 dir = view_dir_from_screen_uv(spec.camera, uv);
      const std::vector<ScatteringResult> column = integrate_scattered_luminance_profile(
          atm, in.transmittance, &in.multiscattering, cam, dir, sun, distances, 2);
      for (int k = 0; k < 32; ++k) {
        const glm::dvec3 end = cam + distances[k] * dir;
        const glm::dvec3 to = demo::aerial_ground_move(end, rb, 10.0, 1.0);
        ScatteringResult ref = column[k];
        if (to != end) {
          ++moved;
          ref = integrate_scattered_luminance(atm, in.transmittance, &in.multiscattering, cam,
                                              glm::normalize(to - cam), sun,
                                              glm::length(to - cam), 2 * (k + 1));
        }
        const double opacity = 1.0 - (ref.transmittance.x + ref.transmittance.y +
                                      ref.transmittance.z) / 3.0;
        // His read of the froxel's own distance: its slice centre, unweighted
        // from 2 km on (before, his read scales slice 3.5; read the texel).
        const demo::AerialRead read = demo::aerial_read(distances[k], 4e3);
        const double w = read.weight == 1.0 ? read.w : texel_center(k, 32);
        const glm::dvec4 his = demo::sample_clamp_3d(ap, uv.x, uv.y, w);
        worst = std::max(worst, rel_diff(his, glm::dvec4(ref.luminance, opacity), 4, 1e-9));
      }
    }
  }
  std::printf("aerial perspective: his froxels against their paths, worst %.3g (%d moved)\n",
              worst, moved);
  EXPECT_GT(moved, 0);
  EXPECT_LT(worst, kBar);
}

TEST(DemoAerialPerspective, HisReadIsSkybakesLookupFromTwoKilometres) {
  const Atmosphere atm = earth_atmosphere();
  const fixtures::SkyLutInputs in = fixtures::bake_sky_lut_inputs(atm);
  const AerialPerspectiveSpec spec = demo_aerial_spec();
  const Texture ap =
      bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, spec, {});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const glm::dvec2 uv(unit(rng), unit(rng));
    // From his half slice (2 km) on; before it his read scales the 2 km value.
    const double d = 2e3 + (140e3 - 2e3) * unit(rng) * unit(rng);
    const demo::AerialRead read = demo::aerial_read(d, 4e3);
    const glm::dvec4 his = read.weight * demo::sample_clamp_3d(ap, uv.x, uv.y, read.w);
    const glm::dvec4 ours = lookup_demo_aerial_perspective(ap, spec.depth_range_m, uv, d);
    worst = std::max(worst, rel_diff(his, ours, 4, 1e-9));
  }
  std::printf("aerial perspective: his read against skybake's lookup, worst %.3g\n", worst);
  EXPECT_LT(worst, kBar);
}

}  // namespace
}  // namespace skybake

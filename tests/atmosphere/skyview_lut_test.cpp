// Tests of the sky-view LUT (atmosphere/skyview_lut.hpp): the latitude /
// longitude mapping pair (round trip at every texel centre and near the
// horizon, zenith / horizon / nadir placement), the direction vectors, an
// empty atmosphere, mirror symmetry about the sun's plane, the forward Mie
// peak, convergence against a 10x finer march, Mars colours, layers and
// thread independence; and rendering from the baked LUTs (sky_render.hpp).
#include "atmosphere/skyview_lut.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_render.hpp"
#include "support/test_atmospheres.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

using fixtures::bake_sky_lut_inputs;
using fixtures::earth_atmosphere;
using fixtures::SkyLutInputs;

double horizon_mu(const Atmosphere& atm, double r) {
  return -std::sqrt(r * r - atm.bottom_radius_m * atm.bottom_radius_m) / r;
}

TEST(SkyviewMapping, RoundTripAtEveryTexelCentre) {
  const Atmosphere atm = earth_atmosphere();
  const int w = 48, h = 27;
  for (double alt : {0.0, 1e3, 50e3, 100e3, 400e3}) {
    const double r = atm.bottom_radius_m + alt;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const glm::dvec2 uv(texel_center(x, w), texel_center(y, h));
        const SkyviewDirection d = view_from_skyview_uv(atm, r, uv, w, h);
        const glm::dvec2 back = skyview_uv_from_view(atm, r, d, w, h);
        EXPECT_NEAR(back.x, uv.x, 1e-12) << alt << " " << x << " " << y;
        EXPECT_NEAR(back.y, uv.y, 1e-9) << alt << " " << x << " " << y;
      }
    }
  }
}

TEST(SkyviewMapping, ZenithHorizonAndNadirPlacement) {
  const Atmosphere atm = earth_atmosphere();
  const int w = 192, h = 108;
  for (double alt : {0.0, 10e3, 100e3, 1000e3}) {
    const double r = atm.bottom_radius_m + alt;
    // Row 0 is the zenith, the last row the nadir (texel centres at the ends).
    EXPECT_NEAR(view_from_skyview_uv(atm, r, {0.5, texel_center(0, h)}, w, h).mu, 1.0, 1e-12);
    EXPECT_NEAR(view_from_skyview_uv(atm, r, {0.5, texel_center(h - 1, h)}, w, h).mu, -1.0, 1e-12);
    // The horizon as seen from r sits at v = 0.5 at every altitude.
    const double mu_h = horizon_mu(atm, r);
    EXPECT_NEAR(skyview_uv_from_view(atm, r, {mu_h, 0.0}, w, h).y, 0.5, 1e-7) << alt;
    // Near the horizon: monotonic (down the texture = down the sky) and the
    // round trip holds on both sides.
    double prev_v = -1.0;
    for (double dmu : {1e-3, 1e-6, 1e-10, 0.0, -1e-10, -1e-6, -1e-3}) {
      const double mu = mu_h + dmu;
      const glm::dvec2 uv = skyview_uv_from_view(atm, r, {mu, 1.0}, w, h);
      EXPECT_GE(uv.y, prev_v) << alt << " " << dmu;
      prev_v = uv.y;
      const SkyviewDirection back = view_from_skyview_uv(atm, r, uv, w, h);
      EXPECT_NEAR(back.mu, mu, 1e-7) << alt << " " << dmu;
      EXPECT_NEAR(back.azimuth_rad, 1.0, 1e-12);
    }
  }
  // At the ground the latitude mapping is the paper's (flipped: row 0 up):
  // x = 0.5 - 0.5 sign(l) sqrt(|l| / (pi / 2)) for the elevation l.
  const double l = 0.3;
  const glm::dvec2 uv = skyview_uv_from_view(atm, atm.bottom_radius_m, {std::sin(l), 0.0}, w, h);
  EXPECT_NEAR(unit_from_texel_coord(uv.y, h), 0.5 - 0.5 * std::sqrt(l / (kPi / 2)), 1e-12);
}

TEST(SkyviewMapping, DirectionVectorsRoundTrip) {
  const glm::dvec3 up(0, 0, 1), sun = glm::normalize(glm::dvec3(0.8, 0, 0.6));
  for (double mu : {0.99, 0.2, -0.3}) {
    for (double az : {0.1, 1.5, 3.0, 4.0, 6.2}) {
      const glm::dvec3 v = skyview_vector_from_direction({mu, az});
      const SkyviewDirection d = skyview_direction_from_vectors(up, v, sun);
      EXPECT_NEAR(d.mu, mu, 1e-12);
      EXPECT_NEAR(d.azimuth_rad, az, 1e-9);
    }
  }
  // The sun's own direction has azimuth 0 in any frame.
  const glm::dvec3 up2 = glm::normalize(glm::dvec3(1, 2, 3));
  const glm::dvec3 sun2 = glm::normalize(glm::dvec3(-1, 0.5, 1));
  EXPECT_NEAR(skyview_direction_from_vectors(up2, sun2, sun2).azimuth_rad, 0.0, 1e-9);
}

TEST(SkyviewLut, EmptyAtmosphereIsBlack) {
  const Atmosphere atm = fixtures::empty_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  SkyviewLutSpec spec{24, 16, 10, StepDistribution::quadratic, {{0.0, 0.5}, {2e5, 1.0}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  for (float v : sky.data) ASSERT_EQ(v, 0.0f);
}

TEST(SkyviewLut, MirrorSymmetricAboutTheSunPlane) {
  // The physics: marching the mirrored direction (y -> -y) gives the same
  // luminance up to rounding, at every texel centre of a layer...
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const SkyviewLutSpec spec{33, 24, 20, StepDistribution::quadratic, {{500.0, 1.2}}};
  const double r = atm.bottom_radius_m + 500.0;
  const glm::dvec3 sun(std::sin(1.2), 0.0, std::cos(1.2));
  for (int y = 0; y < spec.height; y += 3) {
    for (int x = 0; x < spec.width / 2; x += 2) {
      const SkyviewDirection d =
          view_from_skyview_uv(atm, r, {texel_center(x, spec.width), texel_center(y, spec.height)},
                               spec.width, spec.height);
      glm::dvec3 dir = skyview_vector_from_direction(d);
      const ScatteringResult a = integrate_scattered_luminance(
          atm, l.transmittance, &l.multiscattering, {0, 0, r}, dir, sun, INFINITY, 20);
      dir.y = -dir.y;
      const ScatteringResult b = integrate_scattered_luminance(
          atm, l.transmittance, &l.multiscattering, {0, 0, r}, dir, sun, INFINITY, 20);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a.luminance[c], b.luminance[c], 1e-9 * a.luminance[c]) << x << " " << y;
    }
  }
  // ... and the table is mirrored about the sun's plane, u <-> 1 - u (odd
  // width: the middle column is its own mirror image).
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(sky.at(x, y, 0, 0, c), sky.at(sky.width - 1 - x, y, 0, 0, c)) << x << " " << y;
  // Mirrored texel centres are mirrored directions.
  const SkyviewDirection a = view_from_skyview_uv(atm, r, {texel_center(3, 33), 0.3}, 33, 24);
  const SkyviewDirection b = view_from_skyview_uv(atm, r, {texel_center(29, 33), 0.3}, 33, 24);
  EXPECT_NEAR(a.azimuth_rad + b.azimuth_rad, 2.0 * kPi, 1e-12);
  EXPECT_EQ(a.mu, b.mu);
}

TEST(SkyviewLut, ForwardMiePeakPointsAtTheSun) {
  // Strong Mie (10x Earth's aerosols, g = 0.8): at the sun's elevation the
  // texel next to the sun outshines the one opposite it.
  Atmosphere atm = earth_atmosphere();
  atm.components[1].scattering_per_m *= 10.0;
  atm.components[1].absorption_per_m *= 10.0;
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const double sun_zenith = 1.2;
  const SkyviewLutSpec spec{32, 32, 20, StepDistribution::quadratic, {{0.0, sun_zenith}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  const glm::dvec2 uv =
      skyview_uv_from_view(atm, atm.bottom_radius_m, {std::cos(sun_zenith), 0.0}, 32, 32);
  const int row = int(uv.y * 32);
  for (int c = 0; c < 3; ++c)
    EXPECT_GT(sky.at(0, row, 0, 0, c), 2.0 * sky.at(16, row, 0, 0, c)) << c;
}

TEST(SkyviewLut, DefaultStepsMatchATenTimesFinerMarch) {
  // Default march (30 quadratic segments) against 300: within 1.5 % relative
  // on every channel of the sky texels (above the horizon), 3 % below it,
  // for ground, mountain and high-altitude views at noon, 10 degrees and sunset.
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  SkyviewLutSpec spec{
      24, 36, 30, StepDistribution::quadratic, {{0.0, 0.0}, {3e3, 1.4}, {0.0, 1.55}, {30e3, 1.5}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  for (int layer = 0; layer < sky.layers; ++layer) {
    const SkyviewView& v = spec.views[layer];
    const double r = atm.bottom_radius_m + v.altitude_m;
    const glm::dvec3 sun(std::sin(v.sun_zenith_rad), 0.0, std::cos(v.sun_zenith_rad));
    for (int y = 0; y < sky.height; ++y) {
      for (int x = 1; x < sky.width; x += 5) {
        const SkyviewDirection d =
            view_from_skyview_uv(atm, r, {texel_center(x, sky.width), texel_center(y, sky.height)},
                                 sky.width, sky.height);
        const ScatteringResult ref = integrate_scattered_luminance(
            atm, l.transmittance, &l.multiscattering, {0, 0, r}, skyview_vector_from_direction(d),
            sun, INFINITY, 300, {StepDistribution::quadratic, false});
        const double tol = y < sky.height / 2 ? 0.015 : 0.03;
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(sky.at(x, y, 0, layer, c), ref.luminance[c], tol * ref.luminance[c] + 1e-12)
              << "layer " << layer << " x " << x << " y " << y << " c " << c;
      }
    }
  }
}

Atmosphere mars_atmosphere() {
  // docs/reference.md "Atmosphere model" (OpenSpace's Bruneton-based set).
  Atmosphere atm;
  atm.bottom_radius_m = 3386.19e3;
  atm.top_radius_m = atm.bottom_radius_m + 76.98e3;
  atm.ground_albedo = glm::dvec3(0.3);
  const glm::dvec3 mie_sca(53.618e-6);
  atm.components = {
      fixtures::make_component("rayleigh", {19.918e-6, 13.57e-6, 5.75e-6}, glm::dvec3(0.0),
                               exponential_profile(10.44e3), PhaseKind::rayleigh),
      fixtures::make_component("mie", mie_sca, mie_sca / 0.98979 - mie_sca,
                               exponential_profile(3.095e3), PhaseKind::cornette_shanks, 0.85)};
  return atm;
}

TEST(SkyviewLut, MarsButterscotchByDayBlueAroundTheSunAtSunset) {
  // Noon: the sun 30 degrees from the zenith (with the sun exactly overhead
  // the zenith is the sun's own halo, bluish on Mars too). The reversed
  // "Rayleigh" coefficients (red scatters most) colour the open sky red.
  // Sunset: the long slant path strips the red from the sunlight, and the
  // grey dust's forward lobe (g = 0.85) shows that blue light around the sun.
  const Atmosphere atm = mars_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const double noon = 30.0 * kPi / 180.0, sunset = 88.0 * kPi / 180.0;
  const SkyviewLutSpec spec{32, 32, 30, StepDistribution::quadratic, {{0.0, noon}, {0.0, sunset}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  const double r = atm.bottom_radius_m;
  const glm::dvec3 zenith_noon = lookup_skyview(sky, 0, atm, r, {1.0, 0.0});
  EXPECT_GT(zenith_noon.x, 1.2 * zenith_noon.z);
  // Around the sun at sunset: a few degrees beside and above it.
  for (double daz : {0.05, 0.1}) {
    for (double del : {0.0, 0.05}) {
      const double mu = std::cos(sunset - del);
      const glm::dvec3 near_sun = lookup_skyview(sky, 1, atm, r, {mu, daz});
      EXPECT_GT(near_sun.z, 2.0 * near_sun.x) << daz << " " << del;
    }
  }
}

TEST(SkyviewLut, LayersAreIndependentViewsWithMetadata) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const SkyviewLutSpec two{16, 12, 10, StepDistribution::quadratic, {{0.0, 0.3}, {5e3, 1.5}}};
  const SkyviewLutSpec one{16, 12, 10, StepDistribution::quadratic, {{5e3, 1.5}}};
  const Texture a = bake_skyview_lut(atm, l.transmittance, l.multiscattering, two, {});
  const Texture b = bake_skyview_lut(atm, l.transmittance, l.multiscattering, one, {});
  ASSERT_EQ(a.layers, 2);
  EXPECT_EQ(TexelVector(a.data.begin() + a.data.size() / 2, a.data.end()), b.data);
  EXPECT_EQ(meta_double(a.metadata, "layer.0.altitude_m"), 0.0);
  EXPECT_EQ(meta_double(a.metadata, "layer.1.altitude_m"), 5e3);
  EXPECT_EQ(meta_double(a.metadata, "layer.0.sun_zenith_rad"), 0.3);
  EXPECT_EQ(meta_double(a.metadata, "layer.1.sun_zenith_rad"), 1.5);
  EXPECT_EQ(a.metadata.count("layer.2.altitude_m"), 0u);
  EXPECT_EQ(meta_string(a.metadata, "parameterization"), "hillaire2020_skyview");
}

TEST(SkyviewLut, StiffMediaAndSpaceViewsStayFinite) {
  Atmosphere dense = earth_atmosphere();
  dense.components[0].scattering_per_m *= 100.0;
  dense.components[1].g = 0.999;
  Atmosphere tiny = earth_atmosphere();
  tiny.bottom_radius_m = 1e3;
  tiny.top_radius_m = 101e3;
  for (const Atmosphere& atm : {dense, tiny}) {
    const SkyLutInputs l = bake_sky_lut_inputs(atm);
    const double top = atm.top_radius_m - atm.bottom_radius_m;
    const SkyviewLutSpec spec{16,
                              16,
                              20,
                              StepDistribution::quadratic,
                              {{0.0, 0.0}, {0.0, kPi}, {top, 1.5}, {3.0 * top, 0.7}}};
    const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
    for (float v : sky.data) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
    }
  }
}

TEST(SkyviewLut, IdenticalForOneAndTwoThreads) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const SkyviewLutSpec spec{32, 18, 10, StepDistribution::quadratic, {{0.0, 0.5}, {1e3, 1.5}}};
  Texture one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  }
  EXPECT_EQ(one.data, two.data);
}

// ---- sky_render.hpp: what an engine draws from the LUTs ----------------------

TEST(SkyRender, SunDiskIsIlluminanceOverSolidAngleThroughTheAtmosphere) {
  Atmosphere atm = earth_atmosphere();
  atm.sun_illuminance = glm::dvec3(3.0);
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const double mu_s = 0.5;
  const glm::dvec3 sun(std::sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + 10.0);
  const double solid_angle = 2.0 * kPi * (1.0 - std::cos(atm.sun_angular_radius_rad));
  const glm::dvec3 disk = lookup_sun_disk_luminance(atm, l.transmittance, p, sun, sun);
  const glm::dvec3 t = compute_transmittance_to_top(atm, glm::length(p), mu_s, 200);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(disk[c], 3.0 / solid_angle * t[c], 2e-3 * disk[c]);
  // Just outside the disk: nothing. A sun below the horizon is hidden.
  const double off = 1.5 * atm.sun_angular_radius_rad;
  const glm::dvec3 beside(std::sin(std::acos(mu_s) + off), 0.0, std::cos(std::acos(mu_s) + off));
  EXPECT_EQ(lookup_sun_disk_luminance(atm, l.transmittance, p, beside, sun), glm::dvec3(0.0));
  const glm::dvec3 low(std::sqrt(1.0 - 0.01), 0.0, -0.1);
  EXPECT_EQ(lookup_sun_disk_luminance(atm, l.transmittance, p, low, low), glm::dvec3(0.0));
  // From space, outside the atmosphere: the unattenuated disk.
  const glm::dvec3 far(0.0, 0.0, 3.0 * atm.top_radius_m);
  const glm::dvec3 side_sun(1.0, 0.0, 0.0);
  EXPECT_NEAR(lookup_sun_disk_luminance(atm, l.transmittance, far, side_sun, side_sun).x,
              3.0 / solid_angle, 1e-9 / solid_angle);
}

TEST(SkyRender, SkyviewAndRayMarchAgree) {
  // The engine path (sky-view LUT + transmittance LUT for the ground) against
  // the ray march (lit ground included) for a viewer 1 km up, sun at 60
  // degrees: within 3 % for sky directions away from the horizon, ground
  // directions included.
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const double alt = 1e3, sun_zenith = kPi / 3;
  const SkyviewLutSpec spec{192, 108, 30, StepDistribution::quadratic, {{alt, sun_zenith}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
  SkyLuts with_lut{&l.transmittance, &l.multiscattering, &sky, 0};
  SkyLuts march_only{&l.transmittance, &l.multiscattering, nullptr, 0};
  SkyRenderOptions opt;
  opt.sun_disk = false;
  opt.march_steps = 200;
  const glm::dvec3 p(0.0, 0.0, atm.bottom_radius_m + alt);
  const glm::dvec3 sun(std::sin(sun_zenith), 0.0, std::cos(sun_zenith));
  for (double elevation : {1.2, 0.5, 0.15, -0.3, -1.0}) {
    for (double az : {0.3, 1.5, 3.0}) {
      const glm::dvec3 dir(std::cos(elevation) * std::cos(az), std::cos(elevation) * std::sin(az),
                           std::sin(elevation));
      const glm::dvec3 a = render_sky_luminance(atm, with_lut, p, dir, sun, opt);
      const glm::dvec3 b = render_sky_luminance(atm, march_only, p, dir, sun, opt);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a[c], b[c], 0.03 * b[c]) << elevation << " " << az << " " << c;
    }
  }
}

TEST(SkyRender, ImagesFromTheGroundAndFromSpaceAreFiniteAndShowTheSun) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  SkyImageSpec spec;
  spec.width = 32;
  spec.height = 18;
  spec.sun_zenith_rad = kPi / 2 - 0.1;  // sun 0.1 rad up, straight ahead
  spec.camera.pitch_rad = 0.1;
  const SkyviewLutSpec sv{
      64, 36, 30, StepDistribution::quadratic, {{spec.camera.altitude_m, spec.sun_zenith_rad}}};
  const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, sv, {});
  AerialPerspectiveSpec ap_spec;
  ap_spec.camera = spec.camera;
  ap_spec.sun_zenith_rad = spec.sun_zenith_rad;
  const Texture ap =
      bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, ap_spec, {});
  SkyLuts luts{&l.transmittance, &l.multiscattering, &sky, 0, &ap, ap_spec.depth_range_m};
  // The sun disk is far smaller than a pixel here: widen it so a pixel centre hits it.
  Atmosphere big_sun = atm;
  big_sun.sun_angular_radius_rad = 0.05;
  const Texture img = render_sky_image(big_sun, luts, spec, {});
  ASSERT_EQ(img.width, 32);
  float brightest = 0.0f;
  for (float v : img.data) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    brightest = std::max(brightest, v);
  }
  // The image centre looks at the sun.
  EXPECT_EQ(std::max({img.at(15, 8, 0, 0, 0), img.at(16, 8, 0, 0, 0), img.at(15, 9, 0, 0, 0),
                      img.at(16, 9, 0, 0, 0)}),
            brightest);
  // From space, looking straight down at the planet: ray marched, finite, lit.
  SkyImageSpec space = spec;
  space.camera.altitude_m = 3.0 * (atm.top_radius_m - atm.bottom_radius_m);
  space.camera.pitch_rad = -kPi / 2;
  space.sun_zenith_rad = 0.3;
  const Texture planet = render_sky_image(atm, {&l.transmittance, &l.multiscattering}, space, {});
  for (float v : planet.data) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(planet.at(16, 9, 0, 0, 2), 0.0f);
}

// The bake marches a row once for every azimuth and every layer at its
// radius (skyview_row_march.hpp); each texel must still be the march of
// sky_integrator.hpp along its own direction, up to rounding: for viewers on
// the ground, aloft, at the top and above it, suns up, low and below the horizon.
TEST(SkyviewLut, TexelsAreTheMarchOfTheirDirection) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const double top = atm.top_radius_m - atm.bottom_radius_m;
  SkyviewLutSpec spec{14,
                      22,
                      30,
                      StepDistribution::quadratic,
                      {{0.0, 0.3}, {5e3, 1.5}, {0.0, 1.62}, {5e3, 0.0}, {top, 1.0}, {top + 20e3, 1.2}}};
  for (StepDistribution dist : {StepDistribution::quadratic, StepDistribution::uniform}) {
    spec.distribution = dist;
    const Texture sky = bake_skyview_lut(atm, l.transmittance, l.multiscattering, spec, {});
    for (int layer = 0; layer < sky.layers; ++layer) {
      const SkyviewView& v = spec.views[layer];
      const double r = atm.bottom_radius_m + v.altitude_m;
      const glm::dvec3 sun(std::sin(v.sun_zenith_rad), 0.0, std::cos(v.sun_zenith_rad));
      for (int y = 0; y < sky.height; ++y) {
        for (int x = 0; x < sky.width; ++x) {
          const SkyviewDirection d = view_from_skyview_uv(
              atm, r, {texel_center(x, sky.width), texel_center(y, sky.height)}, sky.width,
              sky.height);
          const ScatteringResult ref = integrate_scattered_luminance(
              atm, l.transmittance, &l.multiscattering, {0, 0, r}, skyview_vector_from_direction(d),
              sun, INFINITY, spec.steps, {dist, false});
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sky.at(x, y, 0, layer, c), ref.luminance[c],
                        1e-6 * ref.luminance[c] + 1e-15)
                << "layer " << layer << " x " << x << " y " << y << " c " << c;
        }
      }
    }
  }
}

}  // namespace
}  // namespace skybake

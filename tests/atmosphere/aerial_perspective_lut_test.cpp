// Tests of the aerial-perspective LUT (atmosphere/aerial_perspective_lut.hpp):
// the camera frame and froxel mapping pair, an empty atmosphere, zero
// distance, monotonic growth along a ray, stopping at the ground, agreement
// with a converged march, lookups and thread independence.
#include "atmosphere/aerial_perspective_lut.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "support/test_atmospheres.hpp"
#include "atmosphere/transmittance_lut.hpp"

namespace skybake {
namespace {

using fixtures::bake_sky_lut_inputs;
using fixtures::earth_atmosphere;
using fixtures::SkyLutInputs;

AerialPerspectiveSpec small_spec() {
  AerialPerspectiveSpec spec;
  spec.width = 8;
  spec.height = 8;
  spec.depth = 16;
  spec.camera.altitude_m = 300.0;
  spec.camera.pitch_rad = 0.05;
  spec.camera.yaw_rad = 0.7;
  spec.sun_zenith_rad = 1.0;
  spec.sun_azimuth_rad = 0.4;
  return spec;
}

TEST(AerialPerspectiveMapping, CameraBasisIsOrthonormalAtAnyPitch) {
  for (double pitch : {-kPi / 2, -0.3, 0.0, 0.7, kPi / 2}) {
    SkyCamera cam;
    cam.pitch_rad = pitch;
    cam.yaw_rad = 2.0;
    const CameraBasis b = camera_basis(cam);
    EXPECT_NEAR(glm::length(b.forward), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(b.right), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(b.up), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(b.forward, b.right), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(b.forward, b.up), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(b.right, b.up), 0.0, 1e-12);
    EXPECT_NEAR(b.right.z, 0.0, 1e-15);  // horizontal: no roll
    // The screen centre looks forward; the top of the screen looks up.
    EXPECT_NEAR(glm::length(view_dir_from_screen_uv(cam, {0.5, 0.5}) - b.forward), 0.0, 1e-12);
    EXPECT_GT(glm::dot(view_dir_from_screen_uv(cam, {0.5, 0.0}), b.up), 0.0);
    EXPECT_GT(glm::dot(view_dir_from_screen_uv(cam, {1.0, 0.5}), b.right), 0.0);
  }
}

TEST(AerialPerspectiveMapping, RoundTripAtFroxelCentres) {
  const AerialPerspectiveSpec spec = small_spec();
  for (int z = 0; z < spec.depth; ++z)
    for (int y = 0; y < spec.height; ++y)
      for (int x = 0; x < spec.width; ++x) {
        const glm::dvec3 uvw(texel_center(x, spec.width), texel_center(y, spec.height),
                             texel_center(z, spec.depth));
        const FroxelView v = view_from_aerial_perspective_uvw(spec, uvw);
        EXPECT_NEAR(glm::length(v.view_dir), 1.0, 1e-12);
        const glm::dvec3 back = aerial_perspective_uvw_from_view(spec, v);
        EXPECT_NEAR(back.x, uvw.x, 1e-12);
        EXPECT_NEAR(back.y, uvw.y, 1e-12);
        EXPECT_NEAR(back.z, uvw.z, 1e-12);
      }
  // The first slice centre is half a slice away: 32 km / 32 / 2 = 500 m by default.
  const AerialPerspectiveSpec defaults;
  EXPECT_NEAR(
      view_from_aerial_perspective_uvw(defaults, {0.5, 0.5, texel_center(0, 32)}).distance_m, 500.0,
      1e-9);
}

TEST(AerialPerspectiveLut, EmptyAtmosphereHasNoScatteringAndFullTransmittance) {
  const Atmosphere atm = fixtures::empty_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const Texture ap =
      bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, small_spec(), {});
  for (size_t i = 0; i < ap.data.size(); i += 4) {
    ASSERT_EQ(ap.data[i], 0.0f);
    ASSERT_EQ(ap.data[i + 1], 0.0f);
    ASSERT_EQ(ap.data[i + 2], 0.0f);
    ASSERT_EQ(ap.data[i + 3], 1.0f);
  }
}

TEST(AerialPerspectiveLut, GrowsMonotonicallyAlongEveryRayFromNearlyNothing) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const AerialPerspectiveSpec spec = small_spec();
  const Texture ap = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, spec, {});
  // Densities are at most 1: no path is more opaque than sum_i max_c sigma_t,i.
  double max_sigma_t = 0.0;
  for (const MediumComponent& c : atm.components) {
    const glm::dvec3 e = c.scattering_per_m + c.absorption_per_m;
    max_sigma_t += std::max({e.x, e.y, e.z});
  }
  const double d0 = texel_center(0, spec.depth) * spec.depth_range_m;
  for (int y = 0; y < spec.height; ++y) {
    for (int x = 0; x < spec.width; ++x) {
      // Zero distance: no in-scattering, T = 1; the first slice is close to it.
      const glm::dvec2 uv(texel_center(x, spec.width), texel_center(y, spec.height));
      EXPECT_EQ(lookup_aerial_perspective(ap, spec.depth_range_m, uv, 0.0),
                glm::dvec4(0.0, 0.0, 0.0, 1.0));
      // The first slice (1 km here) is at most as opaque as the densest air.
      EXPECT_GE(ap.at(x, y, 0, 0, 3), std::exp(-max_sigma_t * d0));
      EXPECT_LT(ap.at(x, y, 0, 0, 3), 1.0f);
      for (int z = 1; z < spec.depth; ++z) {
        for (int c = 0; c < 3; ++c) EXPECT_GE(ap.at(x, y, z, 0, c), ap.at(x, y, z - 1, 0, c));
        EXPECT_LE(ap.at(x, y, z, 0, 3), ap.at(x, y, z - 1, 0, 3));
      }
      // Rays above the horizon (upper half of the screen here) never stop:
      // strictly growing in-scattering, strictly falling transmittance.
      if (y < spec.height / 2) {
        for (int z = 1; z < spec.depth; ++z) {
          EXPECT_GT(ap.at(x, y, z, 0, 2), ap.at(x, y, z - 1, 0, 2));
          EXPECT_LT(ap.at(x, y, z, 0, 3), ap.at(x, y, z - 1, 0, 3));
        }
      }
    }
  }
}

TEST(AerialPerspectiveLut, RaysStopAtTheGround) {
  // Camera 300 m up looking 30 degrees down: the centre ray meets the ground
  // at ~600 m; slices past that hold the path up to the ground.
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  AerialPerspectiveSpec spec = small_spec();
  spec.width = spec.height = 1;
  spec.camera.pitch_rad = -kPi / 6;
  const Texture ap = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, spec, {});
  EXPECT_GT(ap.at(0, 0, 0, 0, 2), 0.0f);
  for (int z = 1; z < spec.depth; ++z)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(ap.at(0, 0, z, 0, c), ap.at(0, 0, 0, 0, c));
}

TEST(AerialPerspectiveLut, SlicesMatchAConvergedMarch) {
  // Default 2 segments per slice against one march of 400 segments to the
  // froxel: luminance within 0.5 %, transmittance within 0.02 % (relative).
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  AerialPerspectiveSpec spec = small_spec();
  const Texture ap = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, spec, {});
  const glm::dvec3 pos(0.0, 0.0, atm.bottom_radius_m + spec.camera.altitude_m);
  const glm::dvec3 sun = sun_direction(spec.sun_zenith_rad, spec.sun_azimuth_rad);
  for (int y : {0, 3, 7}) {
    for (int x : {0, 5}) {
      for (int z : {0, 4, 15}) {
        const glm::dvec3 uvw(texel_center(x, spec.width), texel_center(y, spec.height),
                             texel_center(z, spec.depth));
        const FroxelView v = view_from_aerial_perspective_uvw(spec, uvw);
        const ScatteringResult ref = integrate_scattered_luminance(
            atm, l.transmittance, &l.multiscattering, pos, v.view_dir, sun, v.distance_m, 400);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(ap.at(x, y, z, 0, c), ref.luminance[c], 5e-3 * ref.luminance[c]);
        const double mean_t = (ref.transmittance.x + ref.transmittance.y + ref.transmittance.z) / 3;
        EXPECT_NEAR(ap.at(x, y, z, 0, 3), mean_t, 2e-4 * mean_t);
      }
    }
  }
}

TEST(AerialPerspectiveLut, LookupReproducesFroxelsAndFadesBeforeTheFirstSlice) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  const AerialPerspectiveSpec spec = small_spec();
  const Texture ap = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, spec, {});
  const glm::dvec2 uv(texel_center(2, spec.width), texel_center(5, spec.height));
  for (int z : {0, 7, 15}) {
    const double d = texel_center(z, spec.depth) * spec.depth_range_m;
    const glm::dvec4 v = lookup_aerial_perspective(ap, spec.depth_range_m, uv, d);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(v[c], ap.at(2, 5, z, 0, c), 1e-6 * std::abs(v[c]));
  }
  // Halfway to the first slice: halfway between (0, 0, 0, 1) and the slice.
  const double d0 = texel_center(0, spec.depth) * spec.depth_range_m;
  const glm::dvec4 half = lookup_aerial_perspective(ap, spec.depth_range_m, uv, 0.5 * d0);
  EXPECT_NEAR(half.z, 0.5 * ap.at(2, 5, 0, 0, 2), 1e-9);
  EXPECT_NEAR(half.w, 0.5 * (1.0 + ap.at(2, 5, 0, 0, 3)), 1e-9);
}

TEST(AerialPerspectiveLut, SpaceCameraAndStiffMediaStayFinite) {
  Atmosphere dense = earth_atmosphere();
  dense.components[0].scattering_per_m *= 100.0;
  dense.components[1].g = 0.999;
  const SkyLutInputs l = bake_sky_lut_inputs(dense);
  AerialPerspectiveSpec spec = small_spec();
  for (double alt : {0.0, 200e3}) {
    spec.camera.altitude_m = alt;
    spec.camera.pitch_rad = alt > 0 ? -kPi / 2 : 0.0;
    spec.depth_range_m = alt > 0 ? 400e3 : 32e3;
    const Texture ap =
        bake_aerial_perspective_lut(dense, l.transmittance, l.multiscattering, spec, {});
    for (size_t i = 0; i < ap.data.size(); ++i) {
      ASSERT_TRUE(std::isfinite(ap.data[i]));
      ASSERT_GE(ap.data[i], 0.0f);
      if (i % 4 == 3) {
        ASSERT_LE(ap.data[i], 1.0f);
      }
    }
  }
}

TEST(AerialPerspectiveLut, IdenticalForOneAndTwoThreads) {
  const Atmosphere atm = earth_atmosphere();
  const SkyLutInputs l = bake_sky_lut_inputs(atm);
  Texture one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, small_spec(), {});
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_aerial_perspective_lut(atm, l.transmittance, l.multiscattering, small_spec(), {});
  }
  EXPECT_EQ(one.data, two.data);
}

}  // namespace
}  // namespace skybake

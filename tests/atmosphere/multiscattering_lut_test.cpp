// Tests of the multiple-scattering LUT (atmosphere/multiscattering_lut.hpp):
// the direction set, the texel-centre mapping pair, closed forms (no
// scattering -> 0, the lit ground alone), the behaviour of Figure 7 of
// Hillaire 2020, f_ms < 1 on stiff media, lookups, convergence in directions
// and steps, and independence from the thread count.
#include "atmosphere/multiscattering_lut.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "support/test_atmospheres.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

using fixtures::earth_atmosphere;

Texture small_transmittance(const Atmosphere& atm) {
  return bake_transmittance_lut(atm, {128, 64, 40}, {});
}

TEST(FibonacciSphere, UnitVectorsBalancedAndHalfPointDown) {
  for (int n : {16, 64, 65}) {
    const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(n);
    ASSERT_EQ(int(dirs.size()), n);
    glm::dvec3 sum(0.0);
    int down = 0;
    for (const glm::dvec3& d : dirs) {
      EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
      sum += d;
      down += d.z < 0.0;
    }
    // z values are band centres: they sum to exactly 0; x, y nearly cancel.
    EXPECT_NEAR(sum.z, 0.0, 1e-12) << n;
    EXPECT_LT(std::abs(sum.x) + std::abs(sum.y), 0.1 * n) << n;
    if (n % 2 == 0) {
      EXPECT_EQ(down, n / 2);
    }
  }
}

TEST(MultiscatteringMapping, RoundTripAndTexelCentresOnTheBoundaries) {
  const Atmosphere atm = earth_atmosphere();
  const int w = 32, h = 16;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::dvec2 uv(texel_center(x, w), texel_center(y, h));
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(atm, uv, w, h);
      const glm::dvec2 back = multiscattering_uv_from_r_mu_s(atm, p.r, p.mu_s, w, h);
      EXPECT_NEAR(back.x, uv.x, 1e-12);
      EXPECT_NEAR(back.y, uv.y, 1e-12);
    }
  }
  const RadiusSunCosine first =
      r_mu_s_from_multiscattering_uv(atm, {texel_center(0, w), texel_center(0, h)}, w, h);
  EXPECT_NEAR(first.mu_s, -1.0, 1e-12);
  EXPECT_NEAR(first.r, atm.bottom_radius_m, 1e-6);
  const RadiusSunCosine last =
      r_mu_s_from_multiscattering_uv(atm, {texel_center(w - 1, w), texel_center(h - 1, h)}, w, h);
  EXPECT_NEAR(last.mu_s, 1.0, 1e-12);
  EXPECT_NEAR(last.r, atm.top_radius_m, 1e-6);
}

TEST(MultiscatteringMapping, TerminatorRoundTripEdgesAndMonotone) {
  for (const Atmosphere& atm : {earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const MultiscatteringMapping m = terminator_mapping(atm);
    ASSERT_EQ(m.sun, SunMapping::terminator);
    ASSERT_GT(m.width, 0.0);
    const int w = 32, h = 16;
    for (int y = 0; y < h; ++y) {
      double previous = -2.0;
      for (int x = 0; x < w; ++x) {
        const glm::dvec2 uv(texel_center(x, w), texel_center(y, h));
        const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(atm, uv, w, h, m);
        const glm::dvec2 back = multiscattering_uv_from_r_mu_s(atm, p.r, p.mu_s, w, h, m);
        EXPECT_NEAR(back.x, uv.x, 1e-9);
        EXPECT_NEAR(back.y, uv.y, 1e-12);
        EXPECT_GT(p.mu_s, previous);  // strictly increasing along u
        previous = p.mu_s;
      }
      // The first and last texel of every row sit on mu_s = -1 and 1.
      const double r = r_mu_s_from_multiscattering_uv(atm, {0.5, texel_center(y, h)}, w, h, m).r;
      EXPECT_NEAR(sun_cosine_from_unit(m, atm, r, 0.0), -1.0, 1e-12);
      EXPECT_NEAR(sun_cosine_from_unit(m, atm, r, 1.0), 1.0, 1e-12);
    }
    // Texels crowd around the horizon's cosine: the step in mu_s there is
    // smaller than the linear mapping's 2 / (n - 1), and larger at the zenith.
    const double r = atm.bottom_radius_m;
    const double x0 = unit_from_sun_cosine(m, atm, r, 0.0);
    const double step = sun_cosine_from_unit(m, atm, r, x0 + 1.0 / 31) - 0.0;
    EXPECT_LT(step, 2.0 / 31);
    EXPECT_GT(1.0 - sun_cosine_from_unit(m, atm, r, 1.0 - 1.0 / 31), 2.0 / 31);
  }
}

// The quadratic altitude axis: rows at r = Rb + H (y / (n - 1))^2 (the
// closed form of its texel centres), the first and last on the ground and
// the top, and the mapping pair inverse of each other.
TEST(MultiscatteringMapping, QuadraticAltitudeRowsAndRoundTrip) {
  for (const Atmosphere& atm : {earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    MultiscatteringMapping m = terminator_mapping(atm);
    m.altitude = AltitudeMapping::quadratic;
    const double rb = atm.bottom_radius_m, thickness = atm.top_radius_m - rb;
    const int w = 8, h = 32;
    for (int y = 0; y < h; ++y) {
      const double t = double(y) / (h - 1);
      for (int x = 0; x < w; ++x) {
        const glm::dvec2 uv(texel_center(x, w), texel_center(y, h));
        const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(atm, uv, w, h, m);
        EXPECT_NEAR(p.r, rb + thickness * t * t, 1e-9 * atm.top_radius_m) << y;
        const glm::dvec2 back = multiscattering_uv_from_r_mu_s(atm, p.r, p.mu_s, w, h, m);
        EXPECT_NEAR(back.x, uv.x, 1e-9);
        EXPECT_NEAR(back.y, uv.y, 1e-9);
      }
    }
    for (double x_h : {0.0, 1e-4, 0.03, 0.5, 0.97, 1.0})
      EXPECT_NEAR(unit_from_radius(m, atm, radius_from_unit(m, atm, x_h)), x_h, 1e-9);
    // The second row sits (n - 1) times lower than the linear axis's.
    MultiscatteringMapping linear = m;
    linear.altitude = AltitudeMapping::linear;
    EXPECT_NEAR((radius_from_unit(linear, atm, 1.0 / 31) - rb) /
                    (radius_from_unit(m, atm, 1.0 / 31) - rb),
                31.0, 1e-6);
  }
}

TEST(MultiscatteringMapping, RecordedInTheMetadataAndReadBack) {
  const Atmosphere atm = earth_atmosphere();
  MultiscatteringLutSpec spec{8, 8, 16, 10};
  spec.sun_mapping = SunMapping::terminator;
  spec.altitude_mapping = AltitudeMapping::quadratic;
  const Texture ms = bake_multiscattering_lut(atm, small_transmittance(atm), spec, {});
  EXPECT_EQ(meta_string(ms.metadata, "mu_s_mapping"), "terminator");
  EXPECT_EQ(meta_string(ms.metadata, "altitude_mapping"), "quadratic");
  const MultiscatteringMapping m = multiscattering_mapping_of(ms);
  const MultiscatteringMapping expected = terminator_mapping(atm);
  EXPECT_EQ(m.sun, SunMapping::terminator);
  EXPECT_EQ(m.altitude, AltitudeMapping::quadratic);
  EXPECT_EQ(m.width, expected.width);  // 17 significant digits: exact
  EXPECT_EQ(m.offset, expected.offset);
  // The lookup follows the recorded mapping: texel centres read back exactly.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, 8), texel_center(y, 8)}, 8, 8, m);
      const glm::dvec3 v = lookup_multiscattering(ms, atm, p.r, p.mu_s);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], ms.at(x, y, 0, 0, c), 1e-6 * v[c] + 1e-12);
    }
  // A linear table says so, and a table without the key reads as linear.
  const Texture linear = bake_multiscattering_lut(atm, small_transmittance(atm), {8, 8, 16, 10}, {});
  EXPECT_EQ(meta_string(linear.metadata, "mu_s_mapping"), "linear");
  EXPECT_EQ(meta_string(linear.metadata, "altitude_mapping"), "linear");
  const MultiscatteringMapping absent =
      multiscattering_mapping_of(Texture(2, 2, 1, 1, {"R", "G", "B"}));
  EXPECT_EQ(absent.sun, SunMapping::linear);
  EXPECT_EQ(absent.altitude, AltitudeMapping::linear);
  Texture unknown(2, 2, 1, 1, {"R", "G", "B"});
  set_meta(unknown.metadata, "altitude_mapping", std::string("cubic"));
  EXPECT_THROW(multiscattering_mapping_of(unknown), Error);
}

void expect_all_zero(const Texture& tex) {
  for (float v : tex.data) ASSERT_EQ(v, 0.0f);
}

TEST(MultiscatteringLut, NoScatteringAndBlackGroundGiveZero) {
  Atmosphere empty = fixtures::empty_atmosphere();
  empty.ground_albedo = glm::dvec3(0.0);
  expect_all_zero(bake_multiscattering_lut(empty, small_transmittance(empty), {8, 8, 16, 10}, {}));
  // Purely absorbing: ozone alone, and Earth's absorption as a slab.
  Atmosphere ozone = empty;
  ozone.components = {fixtures::earth_ozone()};
  expect_all_zero(bake_multiscattering_lut(ozone, small_transmittance(ozone), {8, 8, 16, 10}, {}));
  Atmosphere slab = fixtures::uniform_slab_atmosphere(glm::dvec3(0.0), glm::dvec3(1e-5));
  slab.ground_albedo = glm::dvec3(0.0);
  expect_all_zero(bake_multiscattering_lut(slab, small_transmittance(slab), {8, 8, 16, 10}, {}));
}

TEST(MultiscatteringLut, LitGroundAloneAtGroundLevel) {
  // No medium, viewer on the ground: the n/2 downward directions see the
  // ground at distance 0 (T = 1) with albedo / pi * mu_s, the others see
  // nothing, f_ms = 0, so Psi_ms = L2 = albedo mu_s / (2 pi).
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.ground_albedo = glm::dvec3(0.1, 0.3, 0.5);
  const Texture t = small_transmittance(atm);
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(64);
  for (double mu_s : {1.0, 0.4, 0.01}) {
    const MultiscatteringSample s =
        compute_multiscattering(atm, t, atm.bottom_radius_m, mu_s, dirs, 20);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.psi_ms[c], atm.ground_albedo[c] * mu_s / (2.0 * kPi), 1e-14) << mu_s;
    EXPECT_EQ(s.f_ms, glm::dvec3(0.0));
  }
  // Sun below the horizon: the ground is unlit.
  EXPECT_EQ(compute_multiscattering(atm, t, atm.bottom_radius_m, -0.2, dirs, 20).psi_ms,
            glm::dvec3(0.0));
}

TEST(MultiscatteringLut, GrowsWithDensityUntilExtinctionWins) {
  // Hillaire 2020 Figure 7: Earth's Rayleigh scattering scaled by 0.1, 1, 10
  // and 50 with the paper's dense-variant profile exp(-h / 20 km), black
  // ground, Psi_ms at the ground for a low sun (mu_s = 0.2, 78 degrees).
  // Thin air: more scatterers, more multiple scattering (0.1 -> 1). Dense
  // air: sunlight is extinguished on its long slant path before it reaches
  // the air around the viewer, so Psi_ms falls (1 -> 10 -> 50) in every
  // channel and at 50x ends far below the thin-air value. (At the ground f_ms
  // cannot exceed 1/2: the downward half of the sphere ends on the black
  // ground at once, so F_ms <= 2 cannot compensate.)
  const double factors[] = {0.1, 1.0, 10.0, 50.0};
  glm::dvec3 psi[4];
  for (int i = 0; i < 4; ++i) {
    Atmosphere atm = fixtures::empty_atmosphere();
    atm.ground_albedo = glm::dvec3(0.0);
    atm.components = {fixtures::earth_rayleigh()};
    atm.components[0].scattering_per_m *= factors[i];
    atm.components[0].density = exponential_profile(20e3);
    const MultiscatteringSample s =
        compute_multiscattering(atm, small_transmittance(atm), atm.bottom_radius_m, 0.2,
                                fibonacci_sphere_directions(64), 20);
    psi[i] = s.psi_ms;
    EXPECT_LE(s.f_ms.z, 0.5 + 1e-12);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(psi[1][c], psi[0][c]) << c;
    EXPECT_LT(psi[2][c], psi[1][c]) << c;
    EXPECT_LT(psi[3][c], psi[2][c]) << c;
    EXPECT_LT(psi[3][c], psi[0][c]) << c;
  }
}

void expect_sane_lut(const Atmosphere& atm, bool expect_no_clamp) {
  const Texture t = small_transmittance(atm);
  const Texture ms = bake_multiscattering_lut(atm, t, {16, 16, 64, 20}, {});
  for (float v : ms.data) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
  const double fms_max = meta_double(ms.metadata, "fms_max");
  EXPECT_GT(fms_max, 0.0);
  if (expect_no_clamp) {
    EXPECT_LT(fms_max, 1.0);
    EXPECT_EQ(meta_int(ms.metadata, "fms_clamped_texels"), 0);
  }
  // Every texel's f_ms, recomputed from scratch, stays below 1.
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(64);
  double seen = 0.0;
  for (int y = 0; y < ms.height; y += 3) {
    for (int x = 0; x < ms.width; x += 3) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, ms.width), texel_center(y, ms.height)}, ms.width, ms.height);
      const MultiscatteringSample s = compute_multiscattering(atm, t, p.r, p.mu_s, dirs, 20);
      for (int c = 0; c < 3; ++c) {
        if (expect_no_clamp) {
          EXPECT_LT(s.f_ms[c], 1.0);
        }
        seen = std::max(seen, s.f_ms[c]);
      }
    }
  }
  EXPECT_LE(seen, fms_max);
}

TEST(MultiscatteringLut, StiffMediaKeepFmsBelowOneAndValuesFinite) {
  expect_sane_lut(earth_atmosphere(), true);
  Atmosphere dense = earth_atmosphere();  // 100x Rayleigh: f_ms gets within 1e-5 of 1
  dense.components[0].scattering_per_m *= 100.0;
  expect_sane_lut(dense, true);
  Atmosphere sharp = earth_atmosphere();
  sharp.components[1].g = 0.999;
  expect_sane_lut(sharp, true);
  Atmosphere tiny = earth_atmosphere();
  tiny.bottom_radius_m = 1e3;
  tiny.top_radius_m = 101e3;
  expect_sane_lut(tiny, true);
  expect_sane_lut(fixtures::tiny_planet_atmosphere(), true);
  // 1000x Rayleigh with no absorption: every ray's transmittance underflows,
  // f_ms rounds to 1 and the clamp has to hold.
  Atmosphere opaque = fixtures::empty_atmosphere();
  opaque.components = {fixtures::earth_rayleigh()};
  opaque.components[0].scattering_per_m *= 1000.0;
  expect_sane_lut(opaque, false);
}

TEST(MultiscatteringLut, LookupReproducesTexelsAndInterpolates) {
  const Atmosphere atm = earth_atmosphere();
  const Texture ms = bake_multiscattering_lut(atm, small_transmittance(atm), {8, 8, 16, 10}, {});
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const RadiusSunCosine p =
          r_mu_s_from_multiscattering_uv(atm, {texel_center(x, 8), texel_center(y, 8)}, 8, 8);
      const glm::dvec3 v = lookup_multiscattering(ms, atm, p.r, p.mu_s);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], ms.at(x, y, 0, 0, c), 1e-7 * v[c] + 1e-12);
    }
  }
  // Halfway between two texel centres along u: their mean.
  const RadiusSunCosine a =
      r_mu_s_from_multiscattering_uv(atm, {texel_center(3, 8), texel_center(2, 8)}, 8, 8);
  const RadiusSunCosine b =
      r_mu_s_from_multiscattering_uv(atm, {texel_center(4, 8), texel_center(2, 8)}, 8, 8);
  const glm::dvec3 mid = lookup_multiscattering(ms, atm, a.r, 0.5 * (a.mu_s + b.mu_s));
  EXPECT_NEAR(mid.z, 0.5 * (ms.at(3, 2, 0, 0, 2) + ms.at(4, 2, 0, 0, 2)), 1e-7);
}

TEST(MultiscatteringLut, DefaultsConvergeTowardAFinerIntegration) {
  // 64 directions x 20 steps against 1024 directions x 200 steps on Earth,
  // from the ground to the top. The error is the direction count's (the
  // steps barely matter): within 2 % relative for a sun 17 degrees or more
  // above the horizon, 5 % at 6 degrees, and near the terminator, where 64
  // directions resolve the planet's shadow coarsely and the values are small,
  // within 1.5 % of the table's largest value.
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  const std::vector<glm::dvec3> coarse = fibonacci_sphere_directions(64);
  const std::vector<glm::dvec3> fine = fibonacci_sphere_directions(1024);
  const double table_max =
      compute_multiscattering(atm, t, atm.bottom_radius_m + 1e3, 1.0, fine, 200).psi_ms.z;
  for (double h : {0.0, 5e3, 30e3, 99e3}) {
    for (double mu_s : {1.0, 0.5, 0.3, 0.1, 0.0, -0.05, -0.2}) {
      const double r = atm.bottom_radius_m + h;
      const glm::dvec3 a = compute_multiscattering(atm, t, r, mu_s, coarse, 20).psi_ms;
      const glm::dvec3 b = compute_multiscattering(atm, t, r, mu_s, fine, 200).psi_ms;
      const double rel = mu_s >= 0.3 ? 0.02 : mu_s >= 0.1 ? 0.05 : 0.0;
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(b[c], table_max);
        EXPECT_NEAR(a[c], b[c], std::max(rel * b[c], 0.015 * table_max)) << h << " " << mu_s;
        if (rel > 0.0) {
          EXPECT_NEAR(a[c], b[c], rel * b[c]) << h << " " << mu_s;
        }
      }
    }
  }
}

TEST(MultiscatteringLut, IdenticalForOneAndTwoThreads) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  Texture one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_multiscattering_lut(atm, t, {16, 16, 32, 10}, {});
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_multiscattering_lut(atm, t, {16, 16, 32, 10}, {});
  }
  EXPECT_EQ(one.data, two.data);
  EXPECT_EQ(one.metadata, two.metadata);
}

// The per-radius lookup (multiscattering_at_radius, then many sun cosines)
// is the lookup, bit for bit, with either sun mapping and either altitude
// mapping.
TEST(MultiscatteringLut, LookupAtARadiusIsTheLookupBitForBit) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  for (int variant = 0; variant < 4; ++variant) {
    const bool terminator = variant & 1;
    MultiscatteringLutSpec spec{8, 8, 16, 10};
    if (terminator) spec.sun_mapping = SunMapping::terminator;
    if (variant & 2) spec.altitude_mapping = AltitudeMapping::quadratic;
    const Texture ms = bake_multiscattering_lut(atm, t, spec, {});
    const MultiscatteringMapping mapping = multiscattering_mapping_of(ms);
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb - 5.0, rb, rb + 30.0, rb + 2e3, rb + 61.7e3, rt, rt + 1e3}) {
      const MultiscatteringAtRadius at = multiscattering_at_radius(ms, mapping, atm, r);
      for (double mu_s : {-1.2, -1.0, -0.4, -0.1, -0.02, 0.0, 0.03, 0.5, 1.0, 1.3}) {
        const glm::dvec3 a = lookup_multiscattering(ms, mapping, atm, r, mu_s);
        const glm::dvec3 b = lookup_multiscattering(ms, at, mu_s);
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(a[c], b[c]) << "variant " << variant << " r " << r << " mu_s " << mu_s;
      }
    }
  }
}

// The bake shares each row's marches among its texels (one radius, many
// suns); every texel must still be compute_multiscattering at its centre.
TEST(MultiscatteringLut, TexelsAreTheIntegralAtTheirCentres) {
  const Atmosphere atm = earth_atmosphere();
  const Texture t = small_transmittance(atm);
  for (DirectionQuadrature quadrature :
       {DirectionQuadrature::fibonacci, DirectionQuadrature::symmetric_gauss}) {
    MultiscatteringLutSpec spec{6, 5, 24, 8};
    spec.sun_mapping = SunMapping::terminator;
    spec.quadrature = quadrature;
    if (quadrature == DirectionQuadrature::symmetric_gauss)
      spec.altitude_mapping = AltitudeMapping::quadratic;
    const Texture ms = bake_multiscattering_lut(atm, t, spec, {});
    const MultiscatteringMapping mapping = multiscattering_mapping_of(ms);
    for (int y = 0; y < ms.height; ++y) {
      for (int x = 0; x < ms.width; ++x) {
        const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
            atm, {texel_center(x, ms.width), texel_center(y, ms.height)}, ms.width, ms.height,
            mapping);
        const SphereRule rule = multiscattering_rule(quadrature, spec.directions, atm, p.r);
        const glm::dvec3 psi =
            compute_multiscattering(atm, t, p.r, p.mu_s, rule, spec.steps).psi_ms;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(ms.at(x, y, 0, 0, c), float(psi[c])) << x << " " << y;
      }
    }
  }
}

}  // namespace
}  // namespace skybake

// sky_irradiance (atmosphere/sky_irradiance.hpp): the L2 basis and the
// clamped-cosine factors against closed forms, the frame's symmetry and
// rotation, the table's reads, and a cut-down twin of the path-tracer
// comparison of sky_irradiance_accuracy_test.cpp.
#include <gtest/gtest.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sh_l2.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "sky_irradiance_reference.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

// A Gauss x midpoint product rule over the whole sphere, weights summing to 4 pi.
void full_sphere_rule(int nz, int nphi, std::vector<glm::dvec3>& dirs, std::vector<double>& w) {
  std::vector<double> z, wz;
  gauss_legendre(nz, z, wz);
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / nphi, s = std::sqrt(1.0 - z[i] * z[i]);
      dirs.push_back({s * std::cos(phi), s * std::sin(phi), z[i]});
      w.push_back(wz[i] * 2.0 * kPi / nphi);
    }
}

TEST(ShL2, BasisIsOrthonormal) {
  std::vector<glm::dvec3> dirs;
  std::vector<double> w;
  full_sphere_rule(8, 16, dirs, w);  // exact for the degree-4 products
  for (int a = 0; a < kShL2Count; ++a)
    for (int b = 0; b < kShL2Count; ++b) {
      double sum = 0.0;
      for (size_t k = 0; k < dirs.size(); ++k)
        sum += w[k] * sh_l2_basis(dirs[k])[a] * sh_l2_basis(dirs[k])[b];
      EXPECT_NEAR(sum, a == b ? 1.0 : 0.0, 1e-12) << a << " " << b;
    }
}

// Radiance 1 over the upper hemisphere: E = pi (1 + n_z) / 2 exactly, and
// its L2 projection decodes to that exactly (the function is linear in n_z,
// bands 0 and 1 only; R&H 2001 eq. 8 gives A_0 = pi, A_1 = 2 pi / 3).
TEST(ShL2, CosineFactorsDecodeAHemisphereExactly) {
  ShRadiance sh;
  sh.fill(glm::dvec3(0.0));
  sh[0] = glm::dvec3(kShY00 * 2.0 * kPi);  // int over z > 0 of Y_00
  sh[2] = glm::dvec3(kShY1 * kPi);         // int over z > 0 of Y_1 z
  // Y_20 integrates to 0 over the hemisphere, Y_11, Y_21, Y_22 by azimuth.
  for (const glm::dvec3 n : fixtures::fibonacci_normals(32))
    EXPECT_NEAR(sh_l2_irradiance(sh, n).x, kPi * (1.0 + n.z) / 2.0, 1e-12);
}

TEST(SkyIrradiance, FrameTurnsTheSunIntoTheXZPlane) {
  const glm::dvec3 up = glm::normalize(glm::dvec3(0.2, -0.3, 0.9));
  const glm::dvec3 sun = glm::normalize(glm::dvec3(-0.5, 0.7, 0.1));
  const SkyFrame f = sky_frame(up, sun);
  EXPECT_NEAR(glm::dot(sun, f.y), 0.0, 1e-14);
  EXPECT_GT(glm::dot(sun, f.x), 0.0);
  EXPECT_NEAR(glm::dot(f.x, f.z), 0.0, 1e-14);
  EXPECT_NEAR(std::cos(f.sun_zenith_rad), glm::dot(sun, up), 1e-14);
  const SkyFrame zenith = sky_frame(up, up);  // any x about a sun at the zenith
  EXPECT_NEAR(glm::dot(zenith.x, up), 0.0, 1e-14);
  EXPECT_NEAR(zenith.sun_zenith_rad, 0.0, 1e-7);
}

// The stored form (ln L_00, L_k / L_00) decodes to the coefficients.
TEST(SkyIrradiance, StoredFormRoundTrips) {
  ShRadiance sh;
  sh.fill(glm::dvec3(0.0));
  const int stored_k[] = {0, 2, 3, 6, 7, 8};
  for (int j = 0; j < kShSymmetricCount; ++j)
    sh[stored_k[j]] = glm::dvec3(3e-7, 0.02, 5.0) * (j == 0 ? 1.0 : 0.3 - 0.1 * j);
  const ShRadiance back = decode_sky_radiance_sh(encode_sky_radiance_sh(sh));
  for (int k = 0; k < kShL2Count; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[k][c], sh[k][c], 1e-14 * sh[0][c]);
}

struct SmallSky {
  Atmosphere atm = fixtures::earth_atmosphere();
  fixtures::SkyLutInputs luts = fixtures::bake_sky_lut_inputs(atm);
  SkyIrradianceSpec spec;
  SmallSky() {
    spec.width = 4;
    spec.height = 3;
    spec.steps = 16;
    spec.below = 3;
    spec.above = 6;
    spec.azimuths = 6;
  }
};

TEST(SkyIrradiance, TexelsHoldTheCoefficientsAndTheReadsTurnWithTheSun) {
  SmallSky s;
  const SkyRadianceSource source =
      psi_ms_source(s.atm, s.luts.transmittance, s.luts.multiscattering, s.spec);
  const Texture table = bake_sky_irradiance(s.atm, source, s.spec, {});
  ASSERT_EQ(table.layers, kShSymmetricCount);
  const double h = sky_irradiance_altitude(s.atm, s.spec, 1);
  const double zenith = sky_irradiance_sun_zenith(s.spec, 2);
  const ShRadiance direct = compute_sky_radiance_sh(s.atm, source, s.spec, h, zenith);
  for (int k : {1, 4, 5}) EXPECT_EQ(direct[k], glm::dvec3(0.0));  // odd in y: not summed
  const ShRadiance read = lookup_sky_radiance_sh(table, h, zenith);
  for (int k = 0; k < kShL2Count; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(read[k][c], direct[k][c], 1e-5 * std::abs(direct[0][c]));
  // The table's frame: sun at azimuth 0. The same sky turned about the
  // zenith by any azimuth, normal with it, gives the same E; a normal
  // mirrored in the sun's plane too.
  const glm::dvec3 up(0.0, 0.0, 1.0), n = glm::normalize(glm::dvec3(0.3, 0.5, -0.2));
  const glm::dvec3 sun0(std::sin(zenith), 0.0, std::cos(zenith));
  const glm::dvec3 e0 = lookup_sky_irradiance(table, n, up, sun0, h);
  EXPECT_NEAR(glm::distance(e0, sh_l2_irradiance(read, n)), 0.0, 1e-12);
  for (double phi : {0.7, 2.0, 4.5}) {
    const glm::dmat3 rz(std::cos(phi), std::sin(phi), 0.0, -std::sin(phi), std::cos(phi), 0.0,
                        0.0, 0.0, 1.0);
    const glm::dvec3 e = lookup_sky_irradiance(table, rz * n, up, rz * sun0, h);
    EXPECT_NEAR(glm::distance(e, e0), 0.0, 1e-9 * glm::length(e0));
  }
  const glm::dvec3 mirrored = lookup_sky_irradiance(table, {n.x, -n.y, n.z}, up, sun0, h);
  EXPECT_NEAR(glm::distance(mirrored, e0), 0.0, 1e-12);
}

// sky_only drops the ground's light: less light for every normal, the
// most for the nadir.
TEST(SkyIrradiance, SkyOnlyDropsTheGround) {
  SmallSky s;
  SkyIrradianceSpec sky = s.spec;
  sky.sky_only = true;
  const ShRadiance all = compute_sky_radiance_sh(
      s.atm, psi_ms_source(s.atm, s.luts.transmittance, s.luts.multiscattering, s.spec), s.spec,
      1000.0, 0.5);
  const ShRadiance only = compute_sky_radiance_sh(
      s.atm, psi_ms_source(s.atm, s.luts.transmittance, s.luts.multiscattering, sky), sky, 1000.0,
      0.5);
  const glm::dvec3 down(0.0, 0.0, -1.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(sh_l2_irradiance(only, down)[c], 0.5 * sh_l2_irradiance(all, down)[c]);
    EXPECT_LT(sh_mean_radiance(only)[c], sh_mean_radiance(all)[c]);
  }
}

// In twilight the table's single scattering (the march of the field
// source, its default 40 steps) against the deterministic quadrature
// (reference/atmosphere_quadrature.hpp): within 2% of each view's value,
// the sun 4 and 8 degrees below the horizon, views toward, across and up.
TEST(SkyIrradiance, TwilightSingleScatteringMatchesTheQuadrature) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {}, {});
  const glm::dvec3 position(0.0, 0.0, atm.bottom_radius_m + 1.0);
  for (double zenith_deg : {94.0, 98.0}) {
    const double z = zenith_deg * kDeg;
    const glm::dvec3 sun(std::sin(z), 0.0, std::cos(z));
    for (double el : {2.0, 10.0, 30.0, 80.0})
      for (double az : {0.0, 90.0}) {
        const glm::dvec3 d(std::cos(el * kDeg) * std::cos(az * kDeg),
                           std::cos(el * kDeg) * std::sin(az * kDeg), std::sin(el * kDeg));
        const glm::dvec3 march = integrate_scattered_luminance(atm, t, nullptr, position, d, sun,
                                                               INFINITY, SkyIrradianceSpec{}.steps)
                                     .luminance;
        const glm::dvec3 exact = reference_single_scattering(atm, position, d, sun, 1e-7).value;
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(march[c], exact[c], 0.02 * exact[c])
              << zenith_deg << " " << el << " " << az << " " << c;
      }
  }
}

// Two psi_ms sources from different tables, the second below the first's
// horizon (`both`), over SmallSky with 5 columns (0, 27, 54, 81 and 108
// degrees).
struct DayAndNight : SmallSky {
  Texture other;
  SkyRadianceSource day, night, both;
  DayAndNight() {
    spec.width = 5;
    other = bake_multiscattering_lut(atm, luts.transmittance, {8, 8, 16, 10}, {});
    day = psi_ms_source(atm, luts.transmittance, luts.multiscattering, spec);
    night = psi_ms_source(atm, luts.transmittance, other, spec);
    both = day;
    both.below_horizon = &night;
  }
  DayAndNight(const DayAndNight&) = delete;
  const SkyRadianceSource& read(double zenith) const { return zenith > 0.5 * kPi ? night : day; }
  const SkyRadianceSource& not_read(double zenith) const {
    return zenith > 0.5 * kPi ? day : night;
  }
};

// Viewers with the sun above their horizon read the first source, the
// others the second, in compute_sky_radiance_sh and in the baked table's
// columns alike; the metadata names both.
TEST(SkyIrradiance, ViewersWithTheSunBelowTheHorizonReadTheTwilightSource) {
  const DayAndNight s;
  const double h = sky_irradiance_altitude(s.atm, s.spec, 1);
  for (int x = 0; x < s.spec.width; ++x) {
    const double zenith = sky_irradiance_sun_zenith(s.spec, x);
    const ShRadiance got = compute_sky_radiance_sh(s.atm, s.both, s.spec, h, zenith);
    EXPECT_EQ(got[0], compute_sky_radiance_sh(s.atm, s.read(zenith), s.spec, h, zenith)[0])
        << zenith / kDeg;
    EXPECT_NE(got[0], compute_sky_radiance_sh(s.atm, s.not_read(zenith), s.spec, h, zenith)[0])
        << zenith / kDeg;
  }
  const Texture table = bake_sky_irradiance(s.atm, s.both, s.spec, {});
  EXPECT_EQ(meta_string(table.metadata, "radiance_source"), "psi_ms");
  EXPECT_EQ(meta_string(table.metadata, "radiance_source_below_horizon"), "psi_ms");
  const ShRadiance last = compute_sky_radiance_sh(s.atm, s.night, s.spec, h, 108.0 * kDeg);
  EXPECT_FLOAT_EQ(table.at(4, 1, 0, 0, 1), float(std::log(last[0].y)));
}

// A single ray (the sky_environment cube's) reads the source of its sun too.
TEST(SkyIrradiance, OneRayReadsTheSourceOfItsSun) {
  const DayAndNight s;
  const glm::dvec3 position(0.0, 0.0, s.atm.bottom_radius_m + 500.0);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.7, 0.2, 0.1));
  for (double zenith : {80.0 * kDeg, 95.0 * kDeg}) {
    const glm::dvec3 sun(std::sin(zenith), 0.0, std::cos(zenith));
    const auto radiance = [&](const SkyRadianceSource& source) {
      return sky_source_radiance(s.atm, source, false, 16, position, dir, sun);
    };
    EXPECT_EQ(radiance(s.both), radiance(s.read(zenith))) << zenith / kDeg;
    EXPECT_NE(radiance(s.both), radiance(s.not_read(zenith))) << zenith / kDeg;
  }
}

// The cut-down twin of the accuracy test: Earth, one altitude and sun,
// the default source (the converged field) against the path tracer, at
// the daylight targets: 3% RMS and 8% max, relative to the mean E over the
// normals.
TEST(SkyIrradiance, EarthDaylightWithinTargetsOfThePathTracer) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {}, {});
  const ConvergedField field = compute_converged_field(atm, t, ConvergedMultiscatteringSpec{}, {});
  SkyRadianceSource source;
  source.transmittance = &t;
  source.field = &field;
  const SkyIrradianceSpec spec;
  const double zenith = 45.0 * kDeg;
  const ShRadiance sh = compute_sky_radiance_sh(atm, source, spec, 0.0, zenith);
  fixtures::ReferenceRule rule;
  rule.below = 4;
  rule.above = 8;
  rule.azimuths = 12;
  rule.samples = 48;
  const fixtures::IrradianceReference ref =
      fixtures::reference_irradiance(atm, 0.0, zenith, rule, 64);
  const fixtures::RelativeErrors e =
      fixtures::relative_errors(ref, [&](glm::dvec3 n) { return sh_l2_irradiance(sh, n); });
  EXPECT_LT(e.rms, 0.03);
  EXPECT_LT(e.max, 0.08);
}

}  // namespace
}  // namespace skybake

// Tests of the ground irradiance tables (atmosphere/irradiance_lut.hpp): the
// mapping, the sun-disk cosine factor, closed forms in an empty atmosphere
// and under an isotropic sky, the tables and their lookup.
#include "atmosphere/irradiance_lut.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "support/test_scattering_specs.hpp"

namespace skybake {
namespace {

const ScatteringShape kSmall = fixtures::tiny_scattering_shape();

TEST(IrradianceMapping, RoundTripAndTexelCentresAtTheEnds) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const int W = 64, H = 16;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const glm::dvec2 uv(texel_center(x, W), texel_center(y, H));
      double r = 0, mu_s = 0;
      r_mu_s_from_irradiance_uv(atm, uv, W, H, r, mu_s);
      ASSERT_GE(r, atm.bottom_radius_m);
      ASSERT_LE(r, atm.top_radius_m);
      ASSERT_LE(std::abs(mu_s), 1.0);
      const glm::dvec2 back = irradiance_uv_from_r_mu_s(atm, r, mu_s, W, H);
      ASSERT_NEAR(back.x, uv.x, 1e-12);
      ASSERT_NEAR(back.y, uv.y, 1e-12);
    }
  double r = 0, mu_s = 0;
  r_mu_s_from_irradiance_uv(atm, {0.5 / W, 0.5 / H}, W, H, r, mu_s);
  EXPECT_EQ(r, atm.bottom_radius_m);
  EXPECT_EQ(mu_s, -1.0);
  r_mu_s_from_irradiance_uv(atm, {1 - 0.5 / W, 1 - 0.5 / H}, W, H, r, mu_s);
  EXPECT_NEAR(r, atm.top_radius_m, 1e-6);
  EXPECT_NEAR(mu_s, 1.0, 1e-15);
}

TEST(SunAverageCosine, ZeroBelowTheDiskCosineAboveContinuousBetween) {
  const double alpha = 0.004675;
  EXPECT_EQ(sun_average_cosine(-2 * alpha, alpha), 0.0);
  EXPECT_EQ(sun_average_cosine(0.5, alpha), 0.5);
  // (mu_s + alpha)^2 / (4 alpha): 0 at -alpha, alpha / 4 at 0, alpha at alpha,
  // with slope 1 there (no kink where it meets mu_s).
  EXPECT_EQ(sun_average_cosine(-alpha, alpha), 0.0);
  EXPECT_NEAR(sun_average_cosine(0.0, alpha), alpha / 4, 1e-18);
  EXPECT_NEAR(sun_average_cosine(alpha, alpha), alpha, 1e-18);
  EXPECT_EQ(sun_average_cosine(0.0, 0.0), 0.0);  // a point sun: no 0 / 0
  EXPECT_EQ(sun_average_cosine(0.25, 0.0), 0.25);
  const double h = 1e-9;
  EXPECT_NEAR((sun_average_cosine(alpha, alpha) - sun_average_cosine(alpha - h, alpha)) / h, 1.0,
              1e-6);
}

TEST(ComputeDirectIrradiance, EmptyAtmosphereIsTheSunTimesTheCosine) {
  // T = 1 everywhere: E_0 = E_sun c(mu_s), i.e. E_sun mu_s away from the
  // horizon and 0 for a sun below it.
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.sun_illuminance = glm::dvec3(1.0, 2.0, 4.0);
  const Texture lut = bake_transmittance_lut(atm, {32, 8, 10}, BakeContext{});
  for (double r : {atm.bottom_radius_m, atm.bottom_radius_m + 30e3, atm.top_radius_m})
    for (double mu_s : {1.0, 0.7, 0.1, 0.02, -0.02, -0.5}) {
      const glm::dvec3 E = compute_direct_irradiance(atm, lut, r, mu_s);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(E[c], atm.sun_illuminance[c] * std::max(mu_s, 0.0)) << r << " " << mu_s;
    }
  const Texture table = bake_direct_irradiance(atm, lut, 64, 16, BakeContext{});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 64; ++x) {
      double r = 0, mu_s = 0;
      r_mu_s_from_irradiance_uv(atm, {texel_center(x, 64), texel_center(y, 16)}, 64, 16, r, mu_s);
      const double expected =
          std::abs(mu_s) < 0.01 ? sun_average_cosine(mu_s, 0.004675) : std::max(mu_s, 0.0);
      ASSERT_NEAR(table.at(x, y, 0, 0, 2), 4.0 * expected, 1e-6) << x << " " << y;
    }
}

TEST(ComputeDirectIrradiance, EarthIsTheSunTimesTransmittanceTimesCosine) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const glm::dvec3 E = compute_direct_irradiance(atm, lut, atm.bottom_radius_m, 0.6);
  const glm::dvec3 T = lookup_transmittance_to_top(lut, atm, atm.bottom_radius_m, 0.6);
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(E[c], 0.6 * T[c]);
}

TEST(ComputeIndirectIrradiance, EmptyAtmosphereGivesNone) {
  // No medium, no scattering at all: the sky is black and so is its light
  // on the ground, whatever the ground albedo.
  const Atmosphere atm = fixtures::empty_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {32, 8, 10}, BakeContext{});
  const SingleScatteringTables single = bake_single_scattering(atm, lut, kSmall, 10, BakeContext{});
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringOrder order{&single.rayleigh, &single.mie, nullptr, &phases};
  const Texture E = bake_indirect_irradiance(atm, kSmall, order, 16, 4, 16, BakeContext{});
  for (float v : E.data) ASSERT_EQ(v, 0.0f);
}

TEST(ComputeIndirectIrradiance, IsotropicSkyGivesPiTimesItsRadiance) {
  // A sky of constant radiance L: E = int_hemisphere L cos(theta) d omega =
  // pi L. The bands' weights are the exact integrals of cos(theta) d omega,
  // so the quadrature is exact for any band count.
  const Atmosphere atm = fixtures::earth_atmosphere();
  Texture sky(kSmall.texture_width(), kSmall.mu_size, kSmall.r_size, 1, {"R", "G", "B"});
  for (size_t i = 0; i < sky.data.size(); i += 3) {
    sky.data[i] = 0.5f;
    sky.data[i + 1] = 1.0f;
    sky.data[i + 2] = 2.0f;
  }
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringOrder order{nullptr, nullptr, &sky, &phases};
  for (int directions : {4, 32})
    for (double mu_s : {1.0, 0.2, -0.1})
      for (double r : {atm.bottom_radius_m, atm.bottom_radius_m + 12e3}) {
        const glm::dvec3 E = compute_indirect_irradiance(atm, kSmall, order, r, mu_s, directions);
        EXPECT_NEAR(E.r, kPi * 0.5, 1e-12);
        EXPECT_NEAR(E.g, kPi * 1.0, 1e-12);
        EXPECT_NEAR(E.b, kPi * 2.0, 1e-12);
      }
}

// compute_indirect_irradiance as the header defines it: one quadrilinear read
// (ScatteringOrder::radiance_at) per direction, where the baker reads each
// band's nu slices once.
glm::dvec3 indirect_one_read_at_a_time(const Atmosphere& atm, const ScatteringOrder& order,
                                       double r, double mu_s, int directions) {
  const int bands = directions / 2, azimuths = directions;
  const double d_theta = 0.5 * kPi / bands, d_phi = kPi / azimuths;
  const glm::dvec3 sun(std::sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  glm::dvec3 E(0.0);
  for (int l = 0; l < bands; ++l) {
    const double theta = (l + 0.5) * d_theta;
    const double s0 = std::sin(l * d_theta), s1 = std::sin((l + 1) * d_theta);
    // cos(theta) d omega over the band, both mirrored halves of each azimuth cell.
    const double weight = (s1 * s1 - s0 * s0) * d_phi;
    for (int m = 0; m < azimuths; ++m) {
      const double phi = (m + 0.5) * d_phi;
      const glm::dvec3 w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      E += weight * order.radiance_at(atm, kSmall, r, w.z, mu_s, glm::dot(w, sun), false);
    }
  }
  return E;
}

TEST(ComputeIndirectIrradiance, EqualsOneReadPerDirection) {
  // Order 1 (two tables, each with its phase) and a radiance table (order 2's
  // shape), at the ground and aloft, suns above and below the horizon.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 4}, BakeContext{});
  const SingleScatteringTables single = bake_single_scattering(atm, lut, kSmall, 20, BakeContext{});
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringOrder order1{&single.rayleigh, &single.mie, nullptr, &phases};
  const ScatteringOrder order2{nullptr, nullptr, &single.mie, &phases};
  for (const ScatteringOrder* order : {&order1, &order2})
    for (double h : {0.0, 2e3, 40e3})
      for (double mu_s : {0.95, 0.3, 0.02, -0.15}) {
        const double r = atm.bottom_radius_m + h;
        const glm::dvec3 fast = compute_indirect_irradiance(atm, kSmall, *order, r, mu_s, 32);
        const glm::dvec3 slow = indirect_one_read_at_a_time(atm, *order, r, mu_s, 32);
        ASSERT_GT(slow.b, 0.0);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(fast[c], slow[c], 1e-12 * slow[c]) << "h " << h << " mu_s " << mu_s;
      }
}

TEST(LookupIrradiance, ExactAtTexelCentresLinearBetween) {
  Texture table(4, 2, 1, 1, {"R", "G", "B"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) table.at(x, y, 0, 0, c) = float(x + 10 * y + 100 * c);
  const Atmosphere atm = fixtures::earth_atmosphere();
  double r = 0, mu_s = 0;
  r_mu_s_from_irradiance_uv(atm, {texel_center(2, 4), texel_center(1, 2)}, 4, 2, r, mu_s);
  EXPECT_NEAR(lookup_irradiance(table, atm, r, mu_s).g, 112.0, 1e-9);
  // Half way between x = 1 and 2 at the ground row (x_mu_s = 0.5: mu_s = 0).
  EXPECT_NEAR(lookup_irradiance(table, atm, atm.bottom_radius_m, 0.0).r, 1.5, 1e-12);
}

}  // namespace
}  // namespace skybake

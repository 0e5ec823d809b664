// Tests of the medium model (atmosphere/medium.hpp): density profiles against
// their defining formulas, layer boundaries, and the sum over components.
#include "atmosphere/medium.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using fixtures::make_component;

// |a - b| <= rel * |b|, for values whose exact form goes through exp().
void expect_rel_near(double a, double b, double rel) {
  EXPECT_NEAR(a, b, rel * std::abs(b));
}

TEST(DensityAt, ExponentialIsExpOfMinusHOverH) {
  const DensityProfile p = exponential_profile(8e3);
  for (double h : {0.0, 1.0, 1e3, 8e3, 25e3, 100e3})
    expect_rel_near(density_at(p, h), std::exp(-h / 8e3), 1e-14);
  EXPECT_EQ(density_at(p, 0.0), 1.0);
}

TEST(DensityAt, ExponentialClampsToOneBelowTheGround) {
  // exp(-h/H) > 1 for h < 0; the profile clamps to [0, 1].
  EXPECT_EQ(density_at(exponential_profile(8e3), -500.0), 1.0);
}

TEST(DensityAt, OzoneTent) {
  // Hillaire 2020: 0 at 10 km, 1 at 25 km, 0 at 40 km, linear in between.
  const DensityProfile p = tent_profile(10e3, 25e3, 40e3);
  EXPECT_EQ(density_at(p, 0.0), 0.0);
  EXPECT_EQ(density_at(p, 5e3), 0.0);
  EXPECT_NEAR(density_at(p, 10e3), 0.0, 1e-15);
  EXPECT_NEAR(density_at(p, 17.5e3), 0.5, 1e-15);
  EXPECT_NEAR(density_at(p, 20e3), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(density_at(p, 25e3), 1.0, 1e-15);
  EXPECT_NEAR(density_at(p, 32.5e3), 0.5, 1e-15);
  EXPECT_NEAR(density_at(p, 40e3), 0.0, 1e-15);
  EXPECT_EQ(density_at(p, 45e3), 0.0);
  EXPECT_EQ(density_at(p, 100e3), 0.0);
  // Continuous at the peak, where it changes layer.
  EXPECT_NEAR(density_at(p, 25e3 - 1e-6), density_at(p, 25e3 + 1e-6), 1e-9);
}

TEST(DensityAt, UniformSlab) {
  const DensityProfile p = uniform_profile(2e3, 5e3);
  EXPECT_EQ(density_at(p, 0.0), 0.0);
  EXPECT_EQ(density_at(p, 1999.0), 0.0);
  EXPECT_EQ(density_at(p, 2e3), 1.0);
  EXPECT_EQ(density_at(p, 4999.0), 1.0);
  EXPECT_EQ(density_at(p, 5e3), 0.0);
  EXPECT_EQ(density_at(p, 80e3), 0.0);
}

TEST(DensityAt, UniformSlabFromTheGround) {
  const DensityProfile p = uniform_profile(0.0, 5e3);
  EXPECT_EQ(density_at(p, 0.0), 1.0);
  EXPECT_EQ(density_at(p, 4999.0), 1.0);
  EXPECT_EQ(density_at(p, 5001.0), 0.0);
}

TEST(DensityAt, MultiLayerBoundariesBelongToTheUpperLayer) {
  DensityLayer a;
  a.width_m = 1e3;
  a.constant_term = 0.2;
  DensityLayer b;
  b.width_m = 2e3;  // covers [1 km, 3 km)
  b.constant_term = 0.5;
  b.linear_term_per_m = 1e-4;  // h is the altitude above the ground, not above the layer
  DensityLayer c;
  c.width_m = 123.0;  // the last layer's width is ignored: it extends to the top
  c.constant_term = 0.9;
  const DensityProfile p{{a, b, c}};
  EXPECT_EQ(density_at(p, 999.0), 0.2);
  EXPECT_NEAR(density_at(p, 1e3), 0.5 + 0.1, 1e-15);
  EXPECT_NEAR(density_at(p, 2e3), 0.5 + 0.2, 1e-15);
  EXPECT_NEAR(density_at(p, 2999.0), 0.5 + 0.2999, 1e-15);
  EXPECT_EQ(density_at(p, 3e3), 0.9);
  EXPECT_EQ(density_at(p, 1e6), 0.9);
}

TEST(DensityAt, ClampsToTheUnitInterval) {
  DensityLayer high;
  high.constant_term = 2.5;
  DensityLayer low;
  low.constant_term = -0.5;
  EXPECT_EQ(density_at(DensityProfile{{high}}, 100.0), 1.0);
  EXPECT_EQ(density_at(DensityProfile{{low}}, 100.0), 0.0);
}

TEST(DensityAt, NoLayersIsZero) {
  EXPECT_EQ(density_at(DensityProfile{}, 0.0), 0.0);
  EXPECT_EQ(density_at(DensityProfile{}, 1e4), 0.0);
}

TEST(SampleMedium, SumsComponents) {
  Atmosphere atm;
  atm.components = {
      make_component("a", {1e-6, 2e-6, 3e-6}, {0.5e-6, 0.0, 0.25e-6}, exponential_profile(8e3)),
      make_component("b", {0.0, 0.0, 0.0}, {4e-6, 5e-6, 6e-6}, tent_profile(10e3, 25e3, 40e3)),
      make_component("c", glm::dvec3(7e-6), glm::dvec3(1e-6), uniform_profile(0.0, 3e3))};
  for (double h : {0.0, 1e3, 17.5e3, 30e3}) {
    const double da = std::exp(-h / 8e3);
    const double db = density_at(tent_profile(10e3, 25e3, 40e3), h);
    const double dc = h < 3e3 ? 1.0 : 0.0;
    const glm::dvec3 sigma_s = da * glm::dvec3(1e-6, 2e-6, 3e-6) + dc * glm::dvec3(7e-6);
    const glm::dvec3 sigma_t = da * glm::dvec3(1.5e-6, 2e-6, 3.25e-6) +
                               db * glm::dvec3(4e-6, 5e-6, 6e-6) + dc * glm::dvec3(8e-6);
    const MediumSample s = sample_medium(atm, h);
    const glm::dvec3 t = extinction_at(atm, h);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(s.scattering[c], sigma_s[c], 1e-14 * sigma_s[c]) << "h " << h << " c " << c;
      EXPECT_NEAR(s.extinction[c], sigma_t[c], 1e-14 * sigma_t[c]) << "h " << h << " c " << c;
      EXPECT_EQ(t[c], s.extinction[c]);
    }
  }
}

TEST(SampleMedium, EmptyAtmosphereIsVacuum) {
  const MediumSample s = sample_medium(fixtures::empty_atmosphere(), 0.0);
  EXPECT_EQ(s.scattering, glm::dvec3(0.0));
  EXPECT_EQ(s.extinction, glm::dvec3(0.0));
}

TEST(SampleMedium, ComponentWithoutLayersContributesNothing) {
  // A component with huge coefficients but no density layers is absent:
  // the sample is bit-identical to the one without it.
  const Atmosphere earth = fixtures::earth_atmosphere();
  Atmosphere with_empty = earth;
  with_empty.components.push_back(
      make_component("ghost", glm::dvec3(1.0), glm::dvec3(1.0), DensityProfile{}));
  for (double h : {0.0, 500.0, 12e3, 60e3}) {
    const MediumSample a = sample_medium(earth, h), b = sample_medium(with_empty, h);
    EXPECT_EQ(a.scattering, b.scattering);
    EXPECT_EQ(a.extinction, b.extinction);
  }
}

TEST(ProfileHelpers, EarthFixtureMatchesReference) {
  // Earth of docs/reference.md: Mie extinction 4.44e-6 /m at the ground; ozone
  // absorbs only; Rayleigh scatters only.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const MediumSample ground = sample_medium(atm, 0.0);
  expect_rel_near(ground.extinction.g, 13.558e-6 + 4.44e-6, 1e-12);
  expect_rel_near(ground.scattering.g, 13.558e-6 + 3.996e-6, 1e-12);
  const MediumSample ozone_peak = sample_medium(atm, 25e3);
  const double rayleigh = std::exp(-25.0 / 8.0), mie = std::exp(-25.0 / 1.2);
  expect_rel_near(ozone_peak.extinction.r, rayleigh * 5.802e-6 + mie * 4.44e-6 + 0.650e-6, 1e-12);
}

}  // namespace
}  // namespace skybake

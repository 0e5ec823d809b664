// sky_light_source_spec (pipeline/atmosphere_specs.hpp): the sky-light
// products make the twilight source only where some viewer has the sun
// below its horizon and twilight_source asks for it, and their daylight
// field is sky_light_field_spec's.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "atmosphere/sky_light_source.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

OutputSpec sky_irradiance_with(nlohmann::json options) {
  OutputSpec spec;
  spec.product = spec.name = "sky_irradiance";
  spec.size = {32, 16};
  options["product"] = "sky_irradiance";
  spec.options = std::move(options);
  return spec;
}

TEST(SkyLightSourceSpec, TwilightSourceOnlyWhereSomeSunIsBelowTheHorizon) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const OutputSpec plain = sky_irradiance_with(nlohmann::json::object());
  EXPECT_EQ(sky_light_source_spec(plain, atm, 108.0 * kDeg).twilight,
            TwilightSource::twilight_field);
  EXPECT_EQ(sky_light_source_spec(plain, atm, 90.0 * kDeg).twilight,
            TwilightSource::daylight_field);
  const OutputSpec field = sky_irradiance_with({{"twilight_source", "converged_field"}});
  EXPECT_EQ(sky_light_source_spec(field, atm, 108.0 * kDeg).twilight,
            TwilightSource::daylight_field);
  const OutputSpec psi = sky_irradiance_with({{"twilight_source", "psi_ms_by_view"}});
  EXPECT_EQ(sky_light_source_spec(psi, atm, 108.0 * kDeg).twilight,
            TwilightSource::psi_ms_by_view);
  const ConvergedMultiscatteringSpec daylight = sky_light_field_spec(plain, atm);
  const SkyLightSourceSpec s = sky_light_source_spec(plain, atm, 108.0 * kDeg);
  EXPECT_EQ(s.field.bruneton.mu_s_size, daylight.bruneton.mu_s_size);
  EXPECT_EQ(s.field.bruneton.mu_size, daylight.bruneton.mu_size);
  EXPECT_DOUBLE_EQ(s.deepest_sun_zenith_rad, 108.0 * kDeg);
}

// The twilight field is finer along the sun than the daylight one, and its
// sun axis reaches past the deepest sun, further than the converged
// default (which stops at the shell's shadow: about 104 degrees on Earth).
TEST(SkyLightSourceSpec, TwilightFieldReachesPastTheDeepestSun) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const ConvergedMultiscatteringSpec daylight = sky_light_field_spec(
      sky_irradiance_with(nlohmann::json::object()), atm);
  for (double deepest : {100.0, 108.0, 130.0}) {
    const ConvergedMultiscatteringSpec t = twilight_field_spec(daylight, deepest * kDeg);
    EXPECT_GT(t.bruneton.mu_s_size, daylight.bruneton.mu_s_size);
    EXPECT_LT(t.mu_s_min_cap, std::cos(deepest * kDeg));
  }
  EXPECT_LT(converged_mu_s_min(atm), std::cos(100.0 * kDeg));
  EXPECT_GT(converged_mu_s_min(atm), std::cos(108.0 * kDeg));
}

}  // namespace
}  // namespace skybake

// sky_light_source_spec (pipeline/atmosphere_specs.hpp): the sky-light
// products make the twilight source only where some viewer has the sun
// below its horizon and twilight_source asks for it, and their daylight
// field is sky_light_field_spec's.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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
  EXPECT_TRUE(sky_light_source_spec(plain, atm, true).twilight);
  EXPECT_FALSE(sky_light_source_spec(plain, atm, false).twilight);
  const OutputSpec field = sky_irradiance_with({{"twilight_source", "converged_field"}});
  EXPECT_FALSE(sky_light_source_spec(field, atm, true).twilight);
  const ConvergedMultiscatteringSpec daylight = sky_light_field_spec(plain, atm);
  const SkyLightSourceSpec s = sky_light_source_spec(plain, atm, true);
  EXPECT_EQ(s.field.bruneton.mu_s_size, daylight.bruneton.mu_s_size);
  EXPECT_EQ(s.field.bruneton.mu_size, daylight.bruneton.mu_size);
  // The twilight field is finer along the sun than the daylight one.
  EXPECT_GT(twilight_field_spec(s.field).bruneton.mu_s_size, s.field.bruneton.mu_s_size);
}

}  // namespace
}  // namespace skybake

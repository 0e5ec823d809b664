// The one place that decides warnings (pipeline/warnings.hpp): each code from
// the numbers a baker records or the texture itself, and none for a table
// that is fine or black by right.
#include "pipeline/warnings.hpp"

#include <gtest/gtest.h>

#include <set>

#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using nlohmann::json;

Scene scene_with(Atmosphere atm) {
  Scene s;
  s.name = "test";
  s.has_atmosphere = true;
  s.atmosphere = std::move(atm);
  return s;
}

OutputSpec spec_of(const std::string& product, json options = json::object()) {
  OutputSpec spec;
  spec.product = product;
  spec.name = product;
  spec.options = std::move(options);
  return spec;
}

Texture lit(int w = 4, int h = 4) {
  Texture t(w, h, 1, 1, {"R", "G", "B"});
  for (float& v : t.data) v = 0.5f;
  return t;
}

std::set<std::string> codes(const std::vector<OutputWarning>& warnings) {
  std::set<std::string> out;
  for (const OutputWarning& w : warnings) out.insert(w.code);
  return out;
}

TEST(Warnings, NoneForATableThatIsFine) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  const json error = {{"max_rel", 0.01}, {"rms_rel", 0.001}, {"queries", 10}, {"reference", ""}};
  EXPECT_TRUE(output_warnings(scene, spec_of("skyview"), lit(), error, json()).empty());
}

TEST(Warnings, OrdersThatStoppedAtTheCapAndATailThatStandsForTheSky) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  Texture t = lit();
  set_meta(t.metadata, "orders", 100);
  set_meta(t.metadata, "tolerance", 1e-3);
  set_meta(t.metadata, "last_residual", 0.0127);
  set_meta(t.metadata, "geometric_tail", glm::dvec3(1.5, 12.0, 55.0));
  const std::vector<OutputWarning> w =
      output_warnings(scene, spec_of("scattering"), t, json(), json());
  ASSERT_EQ(codes(w), (std::set<std::string>{"not_converged", "tail_dominates"}));
  for (const OutputWarning& x : w) {
    const json j = x.json();
    EXPECT_EQ(j["code"], x.code);
    if (x.code == "not_converged") {
      EXPECT_EQ(j["orders"], 100);
      EXPECT_DOUBLE_EQ(j["last_residual"].get<double>(), 0.0127);
      EXPECT_NE(x.message.find("0.0127"), std::string::npos) << x.message;
    } else {
      EXPECT_DOUBLE_EQ(j["geometric_tail"].get<double>(), 55.0);
      EXPECT_NEAR(j["tail_share"].get<double>(), 55.0 * 0.0127, 1e-12);
    }
  }
  // Converged with a large tail factor: the tail is 55 x 1e-4 of a texel.
  set_meta(t.metadata, "last_residual", 1e-4);
  EXPECT_TRUE(output_warnings(scene, spec_of("scattering"), t, json(), json()).empty());
  // Fixed orders record tolerance 0 and no tail.
  set_meta(t.metadata, "tolerance", 0.0);
  set_meta(t.metadata, "last_residual", 0.5);
  set_meta(t.metadata, "geometric_tail", glm::dvec3(0.0));
  EXPECT_TRUE(output_warnings(scene, spec_of("scattering"), t, json(), json()).empty());
}

TEST(Warnings, ClampedMultipleScatteringTransfer) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  Texture t = lit();
  t.data[5] = 1.71f;
  set_meta(t.metadata, "fms_max", 0.999999905);
  set_meta(t.metadata, "fms_clamp", 1.0 - 1e-6);
  set_meta(t.metadata, "fms_clamped_texels", 96);
  const std::vector<OutputWarning> w =
      output_warnings(scene, spec_of("multiscattering"), t, json(), json());
  ASSERT_EQ(codes(w), std::set<std::string>{"fms_clamped"});
  EXPECT_EQ(w[0].numbers["clamped_texels"], 96);
  EXPECT_NEAR(w[0].numbers["max_value"].get<double>(), 1.71, 1e-6);
  set_meta(t.metadata, "fms_clamped_texels", 0);
  EXPECT_TRUE(output_warnings(scene, spec_of("multiscattering"), t, json(), json()).empty());
}

TEST(Warnings, TableThatReturnsMoreThanTheSunlight) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  Texture t = lit();
  set_meta(t.metadata, "energy_out_over_in", glm::dvec3(1.02, 1.28, 0.9));
  const std::vector<OutputWarning> w =
      output_warnings(scene, spec_of("scattering"), t, json(), json());
  ASSERT_EQ(codes(w), std::set<std::string>{"energy_gain"});
  EXPECT_DOUBLE_EQ(w[0].numbers["out_over_in"].get<double>(), 1.28);
  EXPECT_NE(w[0].message.find("1.28"), std::string::npos) << w[0].message;
  // The shell's curvature and absorption only lower out / in: no warning.
  set_meta(t.metadata, "energy_out_over_in", glm::dvec3(0.97, 1.04, 0.6));
  EXPECT_TRUE(output_warnings(scene, spec_of("irradiance"), t, json(), json()).empty());
}

TEST(Warnings, BlackOnlyWhenTheMediumScatters) {
  Texture black = lit();
  for (float& v : black.data) v = 0.0f;
  const Scene earth = scene_with(fixtures::earth_atmosphere());
  EXPECT_EQ(codes(output_warnings(earth, spec_of("skyview"), black, json(), json())),
            std::set<std::string>{"black_output"});
  // A vacuum's sky is black by right; so is the Mie texture of a sky without Mie.
  EXPECT_TRUE(output_warnings(scene_with(fixtures::empty_atmosphere()), spec_of("skyview"), black,
                              json(), json())
                  .empty());
  Atmosphere rayleigh_only = fixtures::empty_atmosphere();
  rayleigh_only.components.push_back(fixtures::earth_rayleigh());
  EXPECT_TRUE(
      output_warnings(scene_with(rayleigh_only), spec_of("single_mie"), black, json(), json())
          .empty());
  // Aerial perspective's A (transmittance) is not scattered light.
  Texture ap(2, 2, 2, 1, {"R", "G", "B", "A"});
  for (size_t i = 3; i < ap.data.size(); i += 4) ap.data[i] = 1.0f;
  EXPECT_EQ(codes(output_warnings(earth, spec_of("aerial_perspective"), ap, json(), json())),
            std::set<std::string>{"black_output"});
}

TEST(Warnings, TransmittanceThatUnderflows) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  Texture t = lit();
  t.data[3 * 2 + 2] = 0.0f;  // blue of texel 2
  const std::vector<OutputWarning> w =
      output_warnings(scene, spec_of("transmittance"), t, json(), json());
  ASSERT_EQ(codes(w), std::set<std::string>{"transmittance_underflow"});
  EXPECT_EQ(w[0].numbers["zero_texels"], 1);
  EXPECT_DOUBLE_EQ(w[0].numbers["fraction"].get<double>(), 1.0 / 16.0);
}

TEST(Warnings, ErrorAboveTheOutputsLimitOrTheProductsDefault) {
  const Scene scene = scene_with(fixtures::earth_atmosphere());
  const json error = {{"max_rel", 0.15}, {"rms_rel", 0.01}, {"queries", 10}, {"reference", ""}};
  // Sky-view's default is 0.1, aerial perspective's 5.
  EXPECT_EQ(codes(output_warnings(scene, spec_of("skyview"), lit(), error, json())),
            std::set<std::string>{"error_above_limit"});
  EXPECT_TRUE(output_warnings(scene, spec_of("aerial_perspective"), lit(), error, json()).empty());
  const std::vector<OutputWarning> w = output_warnings(
      scene, spec_of("aerial_perspective", {{"max_error", 0.05}}), lit(), error, json());
  ASSERT_EQ(codes(w), std::set<std::string>{"error_above_limit"});
  EXPECT_DOUBLE_EQ(w[0].numbers["max_error"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(w[0].numbers["max_rel"].get<double>(), 0.15);
  EXPECT_TRUE(output_warnings(scene, spec_of("skyview", {{"max_error", 0.2}}), lit(), error, json())
                  .empty());
}

TEST(Warnings, TextureThatDoesNotTile) {
  const Scene scene;
  const json seam = {
      {"verdict", "seam"}, {"tiles", false}, {"worst_ratio", 4.0}, {"tolerance", 0.25}};
  EXPECT_EQ(codes(output_warnings(scene, spec_of("noise_shape"), lit(), json(), seam)),
            std::set<std::string>{"not_tileable"});
  const json unbounded = {
      {"verdict", "seam"}, {"tiles", false}, {"worst_ratio", nullptr}, {"tolerance", 0.25}};
  EXPECT_EQ(codes(output_warnings(scene, spec_of("curl"), lit(), json(), unbounded)),
            std::set<std::string>{"not_tileable"});
  for (const char* verdict : {"tiles", "cannot_tell"}) {
    const json other = {{"verdict", verdict}, {"tiles", false}, {"worst_ratio", 0.9}};
    EXPECT_TRUE(output_warnings(scene, spec_of("curl"), lit(), json(), other).empty()) << verdict;
  }
}

TEST(Warnings, LineIsCodeAndMessage) {
  EXPECT_EQ(warning_line({{"code", "black_output"}, {"message", "every colour texel is 0"}}),
            "black_output: every colour texel is 0");
}

}  // namespace
}  // namespace skybake

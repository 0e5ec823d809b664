// Tables baked with "convention": "hillaire_demo" (scene level), read on the
// GL context two ways and compared with skybake's C++ lookups of the
// convention (atmosphere/hillaire_demo_lookups.hpp) at the same (float)
// inputs, reading the same DDS files:
//  - the run-time reads of Hillaire's demo, transcribed in GLSL in our own
//    words from his formulas (LutTransmittanceParamsToUv,
//    GetMultipleScattering, SkyViewLutParamsToUv, the aerial-perspective
//    read of RenderRayMarchingPS), in km as his shaders compute;
//  - runtime/glsl/hillaire_demo.glsl and its HLSL twin.
// Bar: 1e-4 relative (his reads take each table at skybake's physical
// point); float32 evaluation of the mappings is the only difference.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/hillaire_demo_lookups.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/math.hpp"
#include "gl/baked_atmosphere.hpp"
#include "gl/decode_case.hpp"
#include "support/run.hpp"

namespace skybake::gltest {
namespace {

const BakedScene& demo_scene() {
  static const BakedScene scene = bake_scene("gl_hillaire_demo", R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_hillaire_demo",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + test::source_path("presets/atmospheres/earth.json").string() + R"(",
  "convention": "hillaire_demo",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"] },
    { "product": "skyview", "formats": ["dds"],
      "views": [ { "altitude_km": 0.2, "sun_zenith_deg": 60 }, { "altitude_km": 10, "sun_zenith_deg": 88 } ] },
    { "product": "aerial_perspective", "formats": ["dds"],
      "camera": { "altitude_km": 0.5, "pitch_deg": -5, "vertical_fov_deg": 60, "aspect": 1.7777777777777777 },
      "sun": { "zenith_deg": 60, "azimuth_deg": 30 } }
  ]
})");
  return scene;
}

// His reads, in km, written from the demo's formulas; his acos is
// atmosphere_common.glsl's accurate_acos here: llvmpipe's own acos is coarse
// enough to move his sky-view reads by 3e-4 RMS (measured), a property of
// the platform that a GPU's acos does not share.
const char* const kHisReads = R"(
uniform float bottom_km, top_km;
const float kHisPi = 3.1415926535897932384626433832795;
float his_sub_uv(float u, float res) { return (u + 0.5 / res) * (res / (res + 1.0)); }
vec2 his_transmittance_uv(float height, float cos_zenith) {
  float big_h = sqrt(max(0.0, top_km * top_km - bottom_km * bottom_km));
  float rho = sqrt(max(0.0, height * height - bottom_km * bottom_km));
  float disc = height * height * (cos_zenith * cos_zenith - 1.0) + top_km * top_km;
  float d = max(0.0, -height * cos_zenith + sqrt(disc));
  float d_min = top_km - height, d_max = rho + big_h;
  return vec2((d - d_min) / (d_max - d_min), rho / big_h);
}
vec2 his_multiscattering_uv(float height, float cos_sun, float res) {
  vec2 x = clamp(vec2(cos_sun * 0.5 + 0.5, (height - bottom_km) / (top_km - bottom_km)), 0.0, 1.0);
  return vec2(his_sub_uv(x.x, res), his_sub_uv(x.y, res));
}
vec2 his_skyview_uv(bool ground, float cos_zenith, float cos_light_view, float height) {
  float beta = accurate_acos(sqrt(height * height - bottom_km * bottom_km) / height);
  float zenith_horizon = kHisPi - beta;
  float y;
  if (!ground) {
    y = 0.5 * (1.0 - sqrt(1.0 - accurate_acos(cos_zenith) / zenith_horizon));
  } else {
    y = 0.5 * sqrt((accurate_acos(cos_zenith) - zenith_horizon) / beta) + 0.5;
  }
  float x = sqrt(-cos_light_view * 0.5 + 0.5);
  return vec2(his_sub_uv(x, 192.0), his_sub_uv(y, 108.0));
}
vec4 his_aerial(sampler3D volume, vec2 screen_uv, float depth_km) {
  float slice = depth_km / 4.0, weight = 1.0;
  if (slice < 0.5) {
    weight = clamp(slice * 2.0, 0.0, 1.0);
    slice = 0.5;
  }
  return weight * textureLod(volume, vec3(screen_uv, sqrt(slice / 32.0)), 0.0);
}
)";

void set_radii_km(const ComputeProgram& p, const Atmosphere& atm) {
  if (p.has_uniform("bottom_km")) p.set("bottom_km", float(atm.bottom_radius_m * 1e-3));
  if (p.has_uniform("top_km")) p.set("top_km", float(atm.top_radius_m * 1e-3));
}

TEST(HillaireDemoDecode, ManifestRecordsTheConventionAndClampSamplers) {
  const BakedScene& s = demo_scene();
  for (const char* output : {"transmittance", "multiscattering", "skyview", "aerial_perspective"}) {
    EXPECT_EQ(s.entry(output).at("metadata").at("convention"), "hillaire_demo") << output;
    const SamplerState got = s.sampler(output, kRepeatU);
    EXPECT_EQ(got.wrap_s, Wrap::clamp_to_edge) << output;
    EXPECT_EQ(got.wrap_t, Wrap::clamp_to_edge) << output;
  }
  EXPECT_EQ(s.entry("skyview").at("dimensions"), nlohmann::json({192, 108}));
  EXPECT_EQ(s.entry("aerial_perspective").at("dimensions"), nlohmann::json({32, 32, 32}));
  EXPECT_NEAR(s.meta_number("aerial_perspective", "depth_range_m"), 128e3, 1e-9);
}

// His float32 formulas lose digits near the horizon, where the distance to
// the top (transmittance) and the latitude's sqrt (sky-view) are steep in
// mu: within 0.05 of the horizon's cosine his read of his own tables moves
// by up to 1.8e-4 (transmittance) and 5.2e-4 (sky-view) on llvmpipe, a
// property of his arithmetic, not of the layout. His reads are compared
// away from it; skybake's includes everywhere.
constexpr double kHisHorizonMargin = 0.05;

// (r km, mu) with r 100 m to 100 km above the ground and mu at least
// `margin` above the horizon's cosine.
glm::dvec2 transmittance_point(const Atmosphere& atm, size_t i, double margin) {
  const double rb = atm.bottom_radius_m * 1e-3, rt = atm.top_radius_m * 1e-3;
  const double u = unit(i, 1);
  const double r = as_float(rb + 0.1 + (rt - rb - 0.1) * u * u);
  const double mu_h = -std::sqrt(std::max(0.0, 1.0 - rb * rb / (r * r)));
  const double lo = mu_h + std::max(margin, 1e-4);
  return {r, as_float(lo + (1.0 - lo) * unit(i, 2))};
}

TEST(HillaireDemoDecode, HisTransmittanceReadIsSkybakesLookup) {
  const BakedScene& s = demo_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison his = run_case(
      {"his LutTransmittanceParamsToUv", {"atmosphere_common.glsl"}, glsl_table2d("lut") + kHisReads,
       "vec4(textureLod(lut, his_transmittance_uv(q0.x, q0.y), 0.0).rgb, 0.0)", {&tex}, 3},
      s.parameters("transmittance"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec2 p = transmittance_point(atm, i, kHisHorizonMargin);
        q0 = glm::vec4(float(p.x), float(p.y), 0.0f, 0.0f);
        return rgb(lookup_demo_transmittance_to_top(lut, atm, p.x * 1e3, p.y));
      },
      [&](const ComputeProgram& p) { set_radii_km(p, atm); });
  expect_within(his, kCoordinateBar, 2e-5);
  const Comparison ours = run_case(
      {"lookup_demo_transmittance_to_top", {"hillaire_demo.glsl"},
       glsl_table2d("lut"), "vec4(lookup_demo_transmittance_to_top(lut, atm, q0.x, q0.y), 0.0)",
       {&tex}, 3, hlsl_table2d("lut"),
       "float4(lookup_demo_transmittance_to_top(lut, lut_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec2 p = transmittance_point(atm, i, 0.0);
        q0 = glm::vec4(float(p.x * 1e3), float(p.y), 0.0f, 0.0f);
        return rgb(lookup_demo_transmittance_to_top(lut, atm, q0.x, q0.y));
      });
  expect_within(ours, kCoordinateBar);
}

TEST(HillaireDemoDecode, HisMultiscatteringReadIsSkybakesLookup) {
  const BakedScene& s = demo_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("multiscattering");
  const GlTexture tex =
      upload_dds(s.dds_path("multiscattering"), s.sampler("multiscattering", kClamp));
  const double rb = atm.bottom_radius_m * 1e-3, rt = atm.top_radius_m * 1e-3;
  const auto point = [&](size_t i) {
    return glm::dvec2(as_float(rb + (rt - rb) * unit(i, 3)), as_float(2.0 * unit(i, 4) - 1.0));
  };
  const Comparison his = run_case(
      {"his GetMultipleScattering", {"atmosphere_common.glsl"}, glsl_table2d("lut") + kHisReads,
       "vec4(textureLod(lut, his_multiscattering_uv(q0.x, q0.y, 16.0), 0.0).rgb, 0.0)", {&tex}, 3},
      s.parameters("multiscattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec2 p = point(i);
        q0 = glm::vec4(float(p.x), float(p.y), 0.0f, 0.0f);
        return rgb(lookup_demo_multiscattering(lut, atm, p.x * 1e3, p.y));
      },
      [&](const ComputeProgram& p) { set_radii_km(p, atm); });
  expect_within(his, kCoordinateBar, 2e-5);
  const Comparison ours = run_case(
      {"lookup_demo_multiscattering", {"hillaire_demo.glsl"},
       glsl_table2d("lut"), "vec4(lookup_demo_multiscattering(lut, atm, q0.x, q0.y), 0.0)", {&tex},
       3, hlsl_table2d("lut"),
       "float4(lookup_demo_multiscattering(lut, lut_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("multiscattering"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec2 p = point(i);
        q0 = glm::vec4(float(p.x * 1e3), float(p.y), 0.0f, 0.0f);
        return rgb(lookup_demo_multiscattering(lut, atm, q0.x, q0.y));
      });
  expect_within(ours, kCoordinateBar);
}

// Layer, viewer radius (km), mu and azimuth; mu kept `margin` (at least
// 1e-3) off the horizon, where his branch (the ray meets the ground) and the
// latitude's jump meet.
struct SkyPoint {
  int layer;
  double r_km, mu, phi;
};
SkyPoint sky_point(const BakedScene& s, size_t i, double margin) {
  const int layer = int(i % 2);
  const double rb = s.atmosphere.bottom_radius_m * 1e-3;
  const double r =
      as_float(rb + s.meta_number("skyview", "layer." + std::to_string(layer) + ".altitude_m") * 1e-3);
  const double mu_h = -std::sqrt(1.0 - rb * rb / (r * r));
  double mu = 2.0 * unit(i, 5) - 1.0;
  const double m = std::max(margin, 1e-3);
  if (std::abs(mu - mu_h) < m) mu = mu_h + (mu < mu_h ? -m : m);
  return {layer, r, as_float(mu), as_float(2.0 * kPi * unit(i, 6))};
}

TEST(HillaireDemoDecode, HisSkyviewReadIsSkybakesLookup) {
  const BakedScene& s = demo_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("skyview");
  const GlTexture tex = upload_dds(s.dds_path("skyview"), s.sampler("skyview", kClamp), true);
  const double rb = atm.bottom_radius_m;
  const Comparison his = run_case(
      {"his SkyViewLutParamsToUv", {"atmosphere_common.glsl"}, "layout(binding = 0) uniform sampler2DArray lut;" +
                                           std::string(kHisReads),
       "vec4(textureLod(lut, vec3(his_skyview_uv(q0.w > 0.5, q0.y, q0.z, q0.x), q1.x), "
       "0.0).rgb, 0.0)",
       {&tex}, 3},
      s.parameters("skyview"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        // His lightViewCosAngle comes in as a cosine (from the view and sun vectors).
        const SkyPoint p = sky_point(s, i, kHisHorizonMargin);
        const bool ground = ray_intersects_ground(rb, p.r_km * 1e3, p.mu);
        const double cos_phi = as_float(std::cos(p.phi));
        q0 = glm::vec4(float(p.r_km), float(p.mu), float(cos_phi), ground ? 1.0f : 0.0f);
        q1 = glm::vec4(float(p.layer), 0.0f, 0.0f, 0.0f);
        return rgb(lookup_demo_skyview(lut, p.layer, atm, p.r_km * 1e3, {p.mu, std::acos(cos_phi)}));
      },
      [&](const ComputeProgram& p) { set_radii_km(p, atm); });
  expect_within(his, kCoordinateBar, 2e-5);
  const Comparison ours = run_case(
      {"lookup_demo_skyview", {"hillaire_demo.glsl"},
       "layout(binding = 0) uniform sampler2DArray lut;",
       "vec4(lookup_demo_skyview(lut, int(q1.x), atm, q0.x, SkyviewDirection(q0.y, q0.z)), 0.0)",
       {&tex}, 3,
       "Texture2DArray<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
       "float4(lookup_demo_skyview(lut, lut_sampler, int(q1.x), atm, q0.x, "
       "make_skyview_direction(q0.y, q0.z)), 0.0)",
       {}},
      s.parameters("skyview"), [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        const SkyPoint p = sky_point(s, i, 0.0);
        q0 = glm::vec4(float(p.r_km * 1e3), float(p.mu), float(p.phi), 0.0f);
        q1 = glm::vec4(float(p.layer), 0.0f, 0.0f, 0.0f);
        return rgb(lookup_demo_skyview(lut, p.layer, atm, q0.x, {q0.y, q0.z}));
      });
  expect_within(ours, kCoordinateBar);
}

TEST(HillaireDemoDecode, HisAerialPerspectiveReadIsSkybakesLookup) {
  const BakedScene& s = demo_scene();
  const Texture lut = s.texture("aerial_perspective");
  const GlTexture tex =
      upload_dds(s.dds_path("aerial_perspective"), s.sampler("aerial_perspective", kClamp));
  const double range = s.meta_number("aerial_perspective", "depth_range_m");
  // From his half slice (2 km) on: before it his read scales the 2 km value.
  const auto point = [&](size_t i) {
    const double u = unit(i, 9);
    return glm::dvec3(as_float(unit(i, 7)), as_float(unit(i, 8)), as_float(2.0 + 128.0 * u * u));
  };
  const Comparison his = run_case(
      {"his aerial-perspective read", {"atmosphere_common.glsl"}, "layout(binding = 0) uniform sampler3D lut;" +
                                              std::string(kHisReads),
       "his_aerial(lut, q0.xy, q0.z)", {&tex}, 4},
      s.parameters("aerial_perspective"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec3 p = point(i);
        q0 = glm::vec4(float(p.x), float(p.y), float(p.z), 0.0f);
        return lookup_demo_aerial_perspective(lut, range, {p.x, p.y}, p.z * 1e3);
      });
  expect_within(his, kCoordinateBar, 2e-5);
  const Comparison ours = run_case(
      {"lookup_demo_aerial_perspective", {"hillaire_demo.glsl"},
       "layout(binding = 0) uniform sampler3D lut;\nuniform float depth_range_m;",
       "lookup_demo_aerial_perspective(lut, depth_range_m, q0.xy, q0.z)", {&tex}, 4,
       "Texture3D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
       "lookup_demo_aerial_perspective(lut, lut_sampler, extra(0).x, q0.xy, q0.z)",
       {glm::vec4(float(range), 0.0f, 0.0f, 0.0f)}},
      s.parameters("aerial_perspective"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const glm::dvec3 p = point(i);
        // Also the near field, where skybake's read fades from the first slice.
        const double d = i % 8 == 0 ? as_float(2e3 * unit(i, 10)) : as_float(p.z * 1e3);
        q0 = glm::vec4(float(p.x), float(p.y), float(d), 0.0f);
        return lookup_demo_aerial_perspective(lut, double(float(range)), {q0.x, q0.y}, q0.z);
      },
      [&](const ComputeProgram& p) { p.set("depth_range_m", float(range)); });
  expect_within(ours, kCoordinateBar);
}

}  // namespace
}  // namespace skybake::gltest

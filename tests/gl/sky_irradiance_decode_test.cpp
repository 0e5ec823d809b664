// runtime/glsl/sky_irradiance.glsl and its HLSL twin on llvmpipe against
// the C++ lookup_sky_irradiance (atmosphere/sky_irradiance.hpp), reading
// the same DDS file of a real bake, at 4096 (normal, zenith, sun, altitude)
// points in random frames: the axes come from the manifest's metadata, the
// frame is built in the shader. Bar: float32 evaluation of the same
// mapping and of the six-term sum (decode_case.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/sky_irradiance.hpp"
#include "core/math.hpp"
#include "gl/baked_atmosphere.hpp"
#include "gl/decode_case.hpp"
#include "support/run.hpp"

namespace skybake::gltest {
namespace {

const BakedScene& sky_irradiance_scene() {
  static const BakedScene scene = bake_scene("gl_sky_irradiance", R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_sky_irradiance",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + test::source_path("presets/atmospheres/earth.json").string() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"] },
    { "product": "sky_irradiance", "size": [8, 5], "formats": ["dds"],
      "radiance_source": "multiscattering_table", "steps": 8, "rays_below_horizon": 2,
      "rays_above_horizon": 4, "azimuths": 4 }
  ]
})");
  return scene;
}

// A unit vector from two uniform numbers.
glm::dvec3 unit_vector(double a, double b) {
  const double z = 2.0 * a - 1.0, phi = 2.0 * kPi * b, s = std::sqrt(std::max(1.0 - z * z, 0.0));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

glm::vec3 as_float3(glm::dvec3 v) { return glm::vec3(v); }

TEST(SkyIrradianceDecode, ShaderIsTheCppLookup) {
  const BakedScene& s = sky_irradiance_scene();
  // The DDS holds the texels; the axes are in the manifest, as an engine reads them.
  Texture table = s.texture("sky_irradiance");
  ASSERT_EQ(table.layers, kShSymmetricCount);
  for (const char* key : {"max_sun_zenith_deg", "atmosphere_height_m"})
    set_meta(table.metadata, key, s.meta_number("sky_irradiance", key));
  const GlTexture tex =
      upload_dds(s.dds_path("sky_irradiance"), s.sampler("sky_irradiance", kClamp), true);
  const float max_zenith = float(s.meta_number("sky_irradiance", "max_sun_zenith_deg") * kDeg);
  const float height = float(s.meta_number("sky_irradiance", "atmosphere_height_m"));
  const Comparison c = run_case(
      {"sky_irradiance", {"sky_irradiance.glsl"},
       "layout(binding = 0) uniform sampler2DArray lut;\nuniform SkyIrradianceAxes axes;",
       "vec4(sky_irradiance(lut, axes, normalize(q0.xyz), normalize(q1.xyz), "
       "normalize(vec3(q0.w, q1.w, 0.3 * q0.w - 0.2)), 120000.0 * fract(abs(q0.w * 7.31))), 0.0)",
       {&tex}, 3,
       "Texture2DArray<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);\n"
       "SkyIrradianceAxes load_axes() { SkyIrradianceAxes a; a.max_sun_zenith = extra(0).x; "
       "a.height = extra(0).y; return a; }",
       "float4(sky_irradiance(lut, lut_sampler, load_axes(), normalize(q0.xyz), "
       "normalize(q1.xyz), normalize(float3(q0.w, q1.w, 0.3 * q0.w - 0.2)), "
       "120000.0 * frac(abs(q0.w * 7.31))), 0.0)",
       {glm::vec4(max_zenith, height, 0.0f, 0.0f)}},
      s.parameters("sky_irradiance"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        // q0.xyz the normal, q1.xyz the zenith; the sun from q0.w and q1.w
        // (both components of any sign, so every sun zenith occurs).
        q0 = glm::vec4(as_float3(unit_vector(unit(i, 1), unit(i, 2))),
                       float(2.0 * unit(i, 3) - 1.0));
        q1 = glm::vec4(as_float3(unit_vector(unit(i, 4), unit(i, 5))),
                       float(2.0 * unit(i, 6) - 1.0));
        const glm::vec3 n = glm::normalize(glm::vec3(q0));
        const glm::vec3 up = glm::normalize(glm::vec3(q1));
        const glm::vec3 sun = glm::normalize(glm::vec3(q0.w, q1.w, 0.3f * q0.w - 0.2f));
        const float altitude = 120000.0f * (std::abs(q0.w * 7.31f) - std::floor(std::abs(q0.w * 7.31f)));
        return rgb(lookup_sky_irradiance(table, glm::dvec3(n), glm::dvec3(up), glm::dvec3(sun),
                                         double(altitude)));
      },
      [&](const ComputeProgram& p) {
        p.set("axes.max_sun_zenith", max_zenith);
        p.set("axes.height", height);
      });
  expect_within(c, kCoordinateBar, 1e-5);
}

// The cloud-ambient views: the upper hemisphere's mean radiance (GLSL and
// HLSL) and the sphere's (GLSL) against sh_mean_upper_radiance and
// sh_mean_radiance of the C++ read.
TEST(SkyIrradianceDecode, CloudAmbientIsTheCppView) {
  const BakedScene& s = sky_irradiance_scene();
  Texture table = s.texture("sky_irradiance");
  for (const char* key : {"max_sun_zenith_deg", "atmosphere_height_m"})
    set_meta(table.metadata, key, s.meta_number("sky_irradiance", key));
  const GlTexture tex =
      upload_dds(s.dds_path("sky_irradiance"), s.sampler("sky_irradiance", kClamp), true);
  const float max_zenith = float(s.meta_number("sky_irradiance", "max_sun_zenith_deg") * kDeg);
  const float height = float(s.meta_number("sky_irradiance", "atmosphere_height_m"));
  const auto query = [&](bool upper) {
    return [&, upper](size_t i, glm::vec4& q0, glm::vec4&) {
      q0 = glm::vec4(float(120000.0 * unit(i, 1)), float(2.0 * unit(i, 2)), 0.0f, 0.0f);
      const ShRadiance sh = lookup_sky_radiance_sh(table, q0.x, q0.y);
      return rgb(upper ? sh_mean_upper_radiance(sh) : sh_mean_radiance(sh));
    };
  };
  const auto uniforms = [&](const ComputeProgram& p) {
    p.set("axes.max_sun_zenith", max_zenith);
    p.set("axes.height", height);
  };
  const std::string glsl_decl =
      "layout(binding = 0) uniform sampler2DArray lut;\nuniform SkyIrradianceAxes axes;";
  const Comparison upper = run_case(
      {"sky_mean_upper_radiance", {"sky_irradiance.glsl"}, glsl_decl,
       "vec4(sky_mean_upper_radiance(lut, axes, q0.x, q0.y), 0.0)", {&tex}, 3,
       "Texture2DArray<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);\n"
       "SkyIrradianceAxes load_axes() { SkyIrradianceAxes a; a.max_sun_zenith = extra(0).x; "
       "a.height = extra(0).y; return a; }",
       "float4(sky_mean_upper_radiance(lut, lut_sampler, load_axes(), q0.x, q0.y), 0.0)",
       {glm::vec4(max_zenith, height, 0.0f, 0.0f)}},
      s.parameters("sky_irradiance"), query(true), uniforms);
  expect_within(upper, kCoordinateBar, 1e-5);
  const Comparison sphere = run_case(
      {"sky_mean_radiance", {"sky_irradiance.glsl"}, glsl_decl,
       "vec4(sky_mean_radiance(lut, axes, q0.x, q0.y), 0.0)", {&tex}, 3, "", "", {}},
      s.parameters("sky_irradiance"), query(false), uniforms);
  expect_within(sphere, kCoordinateBar, 1e-5);
}

}  // namespace
}  // namespace skybake::gltest

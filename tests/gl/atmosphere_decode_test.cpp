// The engine-side decode of runtime/glsl/ against the C++ lookups: each
// function runs in a compute shader at 4096 query points on textures
// uploaded from the baked DDS files as they are (sampler states of
// docs/runtime.md), and is compared with the C++ lookup_* of the same name
// at the same points (the shader's float inputs, in double), reading the
// same files through our DDS reader. Relative error per channel with the
// floor of core/error_stats.hpp. Bars: 1e-5 where float32 evaluation of
// the same mapping is the only difference, wider where docs/runtime.md
// ("Precision") measures what float32 costs in a mapping.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/gathering_lut.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_render.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error_stats.hpp"
#include "gl/baked_atmosphere.hpp"
#include "gl/decode_case.hpp"
#include "verify/query_points.hpp"

namespace skybake::gltest {
namespace {

// ---- What the shaders are told -----------------------------------------------

// The parameters the tests read from the manifest are the preset's.
TEST(AtmosphereDecode, ManifestParametersMatchThePreset) {
  for (const BakedScene* s : {&separate_mie_scene(), &alpha_mie_scene()}) {
    const GlAtmosphere preset = gl_atmosphere(s->atmosphere);
    for (const char* output : {"transmittance", "scattering", "scattering3d"}) {
      const GlAtmosphere m = s->parameters(output);
      EXPECT_EQ(m.bottom_radius, preset.bottom_radius) << output;
      EXPECT_EQ(m.top_radius, preset.top_radius) << output;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(m.rayleigh_scattering[c], preset.rayleigh_scattering[c]) << output;
        EXPECT_EQ(m.mie_scattering[c], preset.mie_scattering[c]) << output;
      }
      EXPECT_EQ(m.mie_g, preset.mie_g) << output;
      EXPECT_EQ(m.mie_phase, preset.mie_phase) << output;
    }
  }
  const GlAtmosphere irradiance = separate_mie_scene().parameters("irradiance");
  EXPECT_EQ(irradiance.sun_angular_radius, gl_atmosphere(separate_mie_scene().atmosphere).sun_angular_radius);
}

// The sampler state every atmosphere table's metadata asks for (filter,
// wrap_u, wrap_v, wrap_w) is the one docs/runtime.md gives, and the one the
// C++ lookups filter with: linear, clamp to edge, except the sky-view's
// azimuth, which repeats.
TEST(AtmosphereDecode, ManifestSamplersMatchTheDocs) {
  const SamplerState unknown{Filter::nearest, Wrap::repeat, Wrap::repeat, Wrap::repeat};
  const BakedScene& s = separate_mie_scene();
  for (const char* output : {"transmittance", "multiscattering", "skyview", "aerial_perspective",
                             "scattering", "single_mie", "irradiance", "scattering3d",
                             "gathering_sum"}) {
    const SamplerState got = s.sampler(output, unknown);
    const bool volume = s.entry(output).at("dimensions").size() == 3;
    const SamplerState expected = std::string(output) == "skyview" ? kRepeatU : kClamp;
    EXPECT_EQ(got.filter, Filter::linear) << output;
    EXPECT_EQ(got.wrap_s, expected.wrap_s) << output;
    EXPECT_EQ(got.wrap_t, expected.wrap_t) << output;
    if (volume) {
      EXPECT_EQ(got.wrap_r, expected.wrap_r) << output;
    }
  }
}

// ---- Transmittance ----------------------------------------------------------

TEST(AtmosphereDecode, LookupTransmittanceToTop) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"lookup_transmittance_to_top", {"transmittance.glsl"}, glsl_table2d("lut"),
       "vec4(lookup_transmittance_to_top(lut, atm, q0.x, q0.y), 0.0)", {&tex}, 3, hlsl_table2d("lut"),
       "float4(lookup_transmittance_to_top(lut, lut_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const RadiusCosine p = transmittance_query(atm, i);
        q0 = glm::vec4(float(p.r), float(p.mu), 0.0f, 0.0f);
        return rgb(lookup_transmittance_to_top(lut, atm, q0.x, q0.y));
      });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, LookupTransmittance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"lookup_transmittance", {"transmittance.glsl"}, glsl_table2d("lut"),
       "vec4(lookup_transmittance(lut, atm, q0.x, q0.y, q0.z, q0.w > 0.5), 0.0)", {&tex}, 3, hlsl_table2d("lut"),
       "float4(lookup_transmittance(lut, lut_sampler, atm, q0.x, q0.y, q0.z, q0.w > 0.5), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        // Any direction: rays toward the ground read the reversed rays.
        const double r = as_float(transmittance_query(atm, i).r);
        const double mu = as_float(2.0 * unit(i, 90) - 1.0);
        const bool hits = ray_intersects_ground(atm.bottom_radius_m, r, mu);
        const double d = as_float(unit(i, 91) * distance_to_nearest_boundary(
                                                    atm.bottom_radius_m, atm.top_radius_m, r, mu, hits));
        q0 = glm::vec4(float(r), float(mu), float(d), hits ? 1.0f : 0.0f);
        return rgb(lookup_transmittance(lut, atm, r, mu, d, hits));
      });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, LookupSunTransmittance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"lookup_sun_transmittance", {"transmittance.glsl"}, glsl_table2d("lut"),
       "vec4(lookup_sun_transmittance(lut, atm, q0.x, q0.y), 0.0)", {&tex}, 3, hlsl_table2d("lut"),
       "float4(lookup_sun_transmittance(lut, lut_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const double r = as_float(transmittance_query(atm, i).r);
        const double mu_s = as_float(2.0 * unit(i, 92) - 1.0);
        q0 = glm::vec4(float(r), float(mu_s), 0.0f, 0.0f);
        return rgb(lookup_sun_transmittance(lut, atm, r, mu_s));
      });
  expect_within(c, kBar);
}

// ---- Multiple scattering ----------------------------------------------------------

void multiscattering_case(const BakedScene& s, const std::string& what) {
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("multiscattering");
  const MultiscatteringMapping mapping = s.multiscattering_mapping("multiscattering");
  const GlTexture tex = upload_dds(s.dds_path("multiscattering"), s.sampler("multiscattering", kClamp));
  const Comparison c = run_case(
      {what, {"multiscattering.glsl"},
       "layout(binding = 0) uniform sampler2D lut;\nuniform MultiscatteringMapping mapping;",
       "vec4(lookup_multiscattering(lut, mapping, atm, q0.x, q0.y), 0.0)", {&tex}, 3,
       "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);\n" +
           hlsl_load_mapping(),
       "float4(lookup_multiscattering(lut, lut_sampler, load_mapping(), atm, q0.x, q0.y), 0.0)",
       {mapping_extra(mapping)}},
      s.parameters("multiscattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const RadiusCosine p = multiscattering_query(atm, i);
        q0 = glm::vec4(float(p.r), float(p.mu), 0.0f, 0.0f);
        return rgb(lookup_multiscattering(lut, mapping, atm, q0.x, q0.y));
      },
      [&](const ComputeProgram& p) { set_mapping_uniform(p, "mapping", mapping); });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, LookupMultiscattering) {
  ASSERT_EQ(separate_mie_scene().multiscattering_mapping("multiscattering").sun, SunMapping::linear);
  ASSERT_EQ(separate_mie_scene().multiscattering_mapping("multiscattering").altitude,
            AltitudeMapping::linear);
  multiscattering_case(separate_mie_scene(), "lookup_multiscattering (linear sun axis)");
}

TEST(AtmosphereDecode, LookupMultiscatteringTerminatorMapping) {
  const MultiscatteringMapping m = alpha_mie_scene().multiscattering_mapping("multiscattering");
  ASSERT_EQ(m.sun, SunMapping::terminator);
  ASSERT_EQ(m.altitude, AltitudeMapping::quadratic);
  multiscattering_case(alpha_mie_scene(),
                       "lookup_multiscattering (terminator sun axis, quadratic altitude axis)");
}

// ---- Sky-view and aerial perspective -----------------------------------------------

std::vector<double> numbers(const std::string& list) {
  std::vector<double> v;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

std::vector<SkyviewView> skyview_views(const BakedScene& s) {
  const nlohmann::json& meta = s.entry("skyview").at("metadata");
  auto list = [&](const char* key) {
    const nlohmann::json& v = meta.at(key);
    return v.is_array() ? v.get<std::vector<double>>() : numbers(v.get<std::string>());
  };
  std::vector<SkyviewView> views;
  if (meta.contains("layer_altitude_m")) {  // one list per parameter
    const std::vector<double> altitude = list("layer_altitude_m"), zenith = list("layer_sun_zenith_rad");
    for (size_t k = 0; k < altitude.size(); ++k) views.push_back({altitude[k], zenith.at(k)});
    return views;
  }
  for (int k = 0; meta.contains("layer." + std::to_string(k) + ".altitude_m"); ++k)  // a key per layer
    views.push_back({s.meta_number("skyview", "layer." + std::to_string(k) + ".altitude_m"),
                     s.meta_number("skyview", "layer." + std::to_string(k) + ".sun_zenith_rad")});
  return views;
}

TEST(AtmosphereDecode, LookupSkyview) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("skyview");
  const GlTexture tex = upload_dds(s.dds_path("skyview"), s.sampler("skyview", kRepeatU), true);
  const std::vector<SkyviewView> views = skyview_views(s);
  ASSERT_EQ(views.size(), 2u);
  const Comparison c = run_case(
      {"lookup_skyview", {"sky_view.glsl"}, "layout(binding = 0) uniform sampler2DArray lut;",
       "vec4(lookup_skyview(lut, int(q0.x), atm, q0.y, SkyviewDirection(q0.z, q0.w)), 0.0)", {&tex}, 3,
       "Texture2DArray<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
       "float4(lookup_skyview(lut, lut_sampler, int(q0.x), atm, q0.y, make_skyview_direction(q0.z, q0.w)), 0.0)", {}},
      s.parameters("skyview"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const SkyviewQueryPoint p = skyview_query(atm, views, i);
        q0 = glm::vec4(float(p.layer), float(p.r), float(p.view.mu), float(p.view.azimuth_rad));
        return rgb(lookup_skyview(lut, p.layer, atm, q0.y, {q0.z, q0.w}));
      });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, SkyviewDirectionFromVectors) {
  const BakedScene& s = separate_mie_scene();
  const Comparison c = run_case(
      {"skyview_direction_from_vectors (mu, azimuth / 2 pi)", {"sky_view.glsl"}, "",
       "vec4(skyview_direction_from_vectors(vec3(0.0, 0.0, 1.0), q0.xyz, q1.xyz).mu, "
       "skyview_direction_from_vectors(vec3(0.0, 0.0, 1.0), q0.xyz, q1.xyz).azimuth / (2.0 * kPi), 0.0, 0.0)",
       {}, 2, "",
       "float4(skyview_direction_from_vectors(float3(0.0, 0.0, 1.0), q0.xyz, q1.xyz).mu, "
       "skyview_direction_from_vectors(float3(0.0, 0.0, 1.0), q0.xyz, q1.xyz).azimuth / (2.0 * kPi), 0.0, 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        // Directions uniform on the sphere; azimuths near 0 / 2 pi (the
        // wrap) left out, where 1 ulp moves the result by a whole turn.
        auto dir = [&](uint32_t d) {
          const double z = 2.0 * unit(i, d) - 1.0, phi = 2.0 * kPi * unit(i, d + 1);
          const double s = std::sqrt(1.0 - z * z);
          return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
        };
        q0 = glm::vec4(dir(100), 0.0f);
        q1 = glm::vec4(dir(102), 0.0f);
        const SkyviewDirection v = skyview_direction_from_vectors(
            {0.0, 0.0, 1.0}, glm::dvec3(glm::vec3(q0)), glm::dvec3(glm::vec3(q1)));
        const double a = v.azimuth_rad / (2.0 * kPi);
        if (a < 1e-4 || a > 1.0 - 1e-4) {
          q0 = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);  // straight up: mu 1, azimuth 0
          return glm::dvec4(1.0, 0.0, 0.0, 0.0);
        }
        return glm::dvec4(v.mu, a, 0.0, 0.0);
      });
  expect_within(c, kBar);
}

AerialPerspectiveSpec aerial_spec(const BakedScene& s) {
  AerialPerspectiveSpec spec;
  const std::string o = "aerial_perspective";
  spec.depth_range_m = s.meta_number(o, "depth_range_m");
  spec.camera.altitude_m = s.meta_number(o, "camera_altitude_m");
  spec.camera.yaw_rad = s.meta_number(o, "camera_yaw_rad");
  spec.camera.pitch_rad = s.meta_number(o, "camera_pitch_rad");
  spec.camera.vertical_fov_rad = s.meta_number(o, "camera_vertical_fov_rad");
  spec.camera.aspect = s.meta_number(o, "camera_aspect");
  spec.sun_zenith_rad = s.meta_number(o, "sun_zenith_rad");
  spec.sun_azimuth_rad = s.meta_number(o, "sun_azimuth_rad");
  return spec;
}

TEST(AtmosphereDecode, LookupAerialPerspective) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("aerial_perspective");
  const GlTexture tex = upload_dds(s.dds_path("aerial_perspective"), s.sampler("aerial_perspective", kClamp));
  const AerialPerspectiveSpec spec = aerial_spec(s);
  const Comparison c = run_case(
      {"lookup_aerial_perspective", {"sky_view.glsl"},
       "layout(binding = 0) uniform sampler3D lut;\nuniform float depth_range_m;",
       "lookup_aerial_perspective(lut, depth_range_m, q0.xy, q0.z)", {&tex}, 4,
       "Texture3D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
       "lookup_aerial_perspective(lut, lut_sampler, extra(0).x, q0.xy, q0.z)",
       {glm::vec4(float(spec.depth_range_m), 0.0f, 0.0f, 0.0f)}},
      s.parameters("aerial_perspective"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const AerialQueryPoint p = aerial_query(atm, spec, i);
        q0 = glm::vec4(float(p.screen_uv.x), float(p.screen_uv.y), float(p.distance_m), 0.0f);
        return lookup_aerial_perspective(lut, double(float(spec.depth_range_m)),
                                         {q0.x, q0.y}, q0.z);
      },
      [&](const ComputeProgram& p) { p.set("depth_range_m", float(spec.depth_range_m)); });
  expect_within(c, kBar);
}

TEST(AtmosphereDecode, LookupSunDiskLuminance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const double alpha = atm.sun_angular_radius_rad;
  const Comparison c = run_case(
      {"lookup_sun_disk_luminance", {"sky_view.glsl"}, glsl_table2d("lut"),
       "vec4(lookup_sun_disk_luminance(atm, lut, vec3(0.0, 0.0, q0.x), q0.yzw, q1.xyz), 0.0)", {&tex}, 3, hlsl_table2d("lut"),
       "float4(lookup_sun_disk_luminance(atm, lut, lut_sampler, float3(0.0, 0.0, q0.x), q0.yzw, q1.xyz), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        // Viewers from the ground to space; suns from the zenith to below
        // the horizon; view directions within 2 alpha of the sun, away from
        // the disk's edge (0.9 to 1.1 alpha), where one ulp decides.
        const double altitude = 150e3 * unit(i, 110) * unit(i, 110);
        const double zenith = 1.7 * unit(i, 111);
        double offset = 2.0 * alpha * unit(i, 112);
        if (std::abs(offset - alpha) < 0.1 * alpha) offset = 0.5 * alpha;
        const double phi = 2.0 * kPi * unit(i, 113);
        const glm::dvec3 sun = sun_direction(zenith, 0.0);
        const glm::dvec3 t1 = glm::normalize(glm::cross(sun, glm::dvec3(0.0, 1.0, 0.0)));
        const glm::dvec3 t2 = glm::cross(sun, t1);
        const glm::dvec3 view = std::cos(offset) * sun +
                                std::sin(offset) * (std::cos(phi) * t1 + std::sin(phi) * t2);
        q0 = glm::vec4(float(atm.bottom_radius_m + altitude), glm::vec3(view));
        q1 = glm::vec4(glm::vec3(sun), 0.0f);
        const glm::dvec3 v = glm::dvec3(q0.y, q0.z, q0.w), sd = glm::dvec3(glm::vec3(q1));
        // Rays that graze the ground within float precision are left out.
        const double r = q0.x, mu = v.z / glm::length(v);
        if (std::abs(mu + std::sqrt(1.0 - atm.bottom_radius_m * atm.bottom_radius_m / (r * r))) < 1e-4)
          q0.x = float(atm.bottom_radius_m + 1e3);
        return rgb(lookup_sun_disk_luminance(atm, lut, {0.0, 0.0, double(q0.x)}, v, sd));
      });
  expect_within(c, kBar);
}

}  // namespace
}  // namespace skybake::gltest

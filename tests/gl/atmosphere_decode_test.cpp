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
#include "atmosphere/query_points.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_render.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error_stats.hpp"
#include "gl/baked_atmosphere.hpp"

namespace skybake::gltest {
namespace {

constexpr size_t kQueries = 4096;

// Fills q0, q1 with the shader's inputs for query i and returns the C++
// reference at exactly those (float) inputs.
using QueryFn = std::function<glm::dvec4(size_t i, glm::vec4& q0, glm::vec4& q1)>;

struct DecodeCase {
  std::string what;                    // the function, for the printed line
  std::vector<std::string> includes;   // runtime/glsl files
  std::string declarations;            // samplers and uniforms
  std::string expression;              // vec4 from q0, q1, atm
  std::vector<const GlTexture*> units;  // bound to units 0, 1, ...
  int channels = 3;
  // The HLSL twin (hlsl_query_shader), run on the same textures and points.
  std::string hlsl_declarations;
  std::string hlsl_expression;
  std::vector<glm::vec4> extra;  // extra(k) of the HLSL shader
};

// Compares and prints one run, with the worst point's inputs and values.
Comparison report(const std::string& what, const std::vector<glm::vec4>& queries,
                  const std::vector<glm::vec4>& gl, const std::vector<glm::dvec4>& cpu,
                  int channels) {
  const Comparison result = compare(gl, cpu, channels);
  print_comparison(what, result);
  const size_t w = result.worst_query;
  const glm::vec4 q0 = queries[2 * w], q1 = queries[2 * w + 1];
  std::printf("             worst: q0 (%.9g, %.9g, %.9g, %.9g) q1 (%.9g, %.9g, %.9g, %.9g)\n"
              "             GL (%.9g, %.9g, %.9g, %.9g) C++ (%.9g, %.9g, %.9g, %.9g)\n",
              q0.x, q0.y, q0.z, q0.w, q1.x, q1.y, q1.z, q1.w, gl[w].x, gl[w].y, gl[w].z, gl[w].w,
              cpu[w].x, cpu[w].y, cpu[w].z, cpu[w].w);
  return result;
}

Comparison run_case(const DecodeCase& c, const GlAtmosphere& atm, const QueryFn& query,
                    const std::function<void(const ComputeProgram&)>& uniforms = {}) {
  GlContext::shared();
  const ComputeProgram program =
      compile_compute(c.includes, query_shader(c.declarations, c.expression));
  set_atmosphere_uniform(program, "atm", atm);
  if (uniforms) uniforms(program);
  for (size_t u = 0; u < c.units.size(); ++u) c.units[u]->bind(unsigned(u));
  std::vector<glm::vec4> queries(2 * kQueries, glm::vec4(0.0f));
  std::vector<glm::dvec4> cpu(kQueries);
  for (size_t i = 0; i < kQueries; ++i) cpu[i] = query(i, queries[2 * i], queries[2 * i + 1]);
  Comparison result = report(c.what, queries, run_queries(program, queries), cpu, c.channels);
  if (c.hlsl_expression.empty()) return result;
  std::vector<std::string> hlsl_includes;
  for (const std::string& name : c.includes)
    hlsl_includes.push_back(name.substr(0, name.size() - 5) + ".hlsl");
  const ComputeProgram hlsl = compile_compute_hlsl(
      hlsl_includes, hlsl_query_shader(c.hlsl_declarations, c.hlsl_expression));
  for (size_t u = 0; u < c.units.size(); ++u) c.units[u]->bind(unsigned(u));
  const Comparison twin = report(c.what + " [HLSL]", queries,
                                 run_hlsl_queries(hlsl, atm, c.extra, queries), cpu, c.channels);
  // The worse of the two against the bars.
  result.stats.max_rel = std::max(result.stats.max_rel, twin.stats.max_rel);
  result.stats.rms_rel = std::max(result.stats.rms_rel, twin.stats.rms_rel);
  return result;
}

// Bars on the largest relative error: kBar where evaluating the same mapping
// in float32 is the only difference; kCoordinateBar for the reads near a
// steep texel-to-texel change (the horizon, the terminator), where a float32
// texture coordinate's resolution, about n 2^-24 of a texel, moves the
// value by up to a few 1e-5 (docs/runtime.md "Precision"). The RMS over all
// points stays below kRmsBar for every function.
constexpr double kBar = 1e-5, kCoordinateBar = 1e-4, kRmsBar = 5e-6;
// S(camera) - T S(point) cancels (and goes negative, Bruneton's known
// artefact, where the table's interpolation overshoots): its error is that
// of the two reads relative to their difference.
constexpr double kDifferenceBar = 5e-3, kDifferenceRmsBar = 1e-4;

void expect_within(const Comparison& c, double max_bar, double rms_bar = kRmsBar) {
  EXPECT_LE(c.stats.max_rel, max_bar);
  EXPECT_LE(c.stats.rms_rel, rms_bar);
}

const SamplerState kClamp{Filter::linear, Wrap::clamp_to_edge, Wrap::clamp_to_edge,
                          Wrap::clamp_to_edge};
// The sky-view's azimuth wraps (docs/runtime.md "Sky-view").
const SamplerState kRepeatU{Filter::linear, Wrap::repeat, Wrap::clamp_to_edge,
                            Wrap::clamp_to_edge};

double unit(size_t i, uint32_t dim) { return query_unit(i, dim); }

glm::dvec4 rgb(glm::dvec3 v) { return glm::dvec4(v, 0.0); }

ScatteringShape shape_of(const BakedScene& s) {
  ScatteringShape shape;
  shape.r_size = int(s.meta_number("scattering", "r_size"));
  shape.mu_size = int(s.meta_number("scattering", "mu_size"));
  shape.mu_s_size = int(s.meta_number("scattering", "mu_s_size"));
  shape.nu_size = int(s.meta_number("scattering", "nu_size"));
  shape.mu_s_min = s.meta_number("scattering", "mu_s_min");
  return shape;
}

std::vector<glm::vec4> shape_extra(const ScatteringShape& shape) {
  return {glm::vec4(float(shape.r_size), float(shape.mu_size), float(shape.mu_s_size),
                    float(shape.nu_size)),
          glm::vec4(float(shape.mu_s_min), 0.0f, 0.0f, 0.0f)};
}

std::vector<glm::vec4> shape3d_extra(const Texture& t) {
  return {glm::vec4(float(t.width), float(t.height), float(t.depth), 0.0f)};
}

void set_shape(const ComputeProgram& p, const ScatteringShape& shape) {
  p.set("shape.r_size", shape.r_size);
  p.set("shape.mu_size", shape.mu_size);
  p.set("shape.mu_s_size", shape.mu_s_size);
  p.set("shape.nu_size", shape.nu_size);
  p.set("shape.mu_s_min", float(shape.mu_s_min));
}

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

// ---- Transmittance ----------------------------------------------------------

TEST(AtmosphereDecode, LookupTransmittanceToTop) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"lookup_transmittance_to_top", {"transmittance.glsl"}, "layout(binding = 0) uniform sampler2D lut;",
       "vec4(lookup_transmittance_to_top(lut, atm, q0.x, q0.y), 0.0)", {&tex}, 3, "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
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
      {"lookup_transmittance", {"transmittance.glsl"}, "layout(binding = 0) uniform sampler2D lut;",
       "vec4(lookup_transmittance(lut, atm, q0.x, q0.y, q0.z, q0.w > 0.5), 0.0)", {&tex}, 3, "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
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
      {"lookup_sun_transmittance", {"transmittance.glsl"}, "layout(binding = 0) uniform sampler2D lut;",
       "vec4(lookup_sun_transmittance(lut, atm, q0.x, q0.y), 0.0)", {&tex}, 3, "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
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
       "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);\n"
       "MultiscatteringMapping load_mapping() {\n  MultiscatteringMapping m;\n"
       "  m.sun = int(extra(0).x);\n  m.width = extra(0).y;\n  m.offset = extra(0).z;\n  return m;\n}\n",
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
  multiscattering_case(separate_mie_scene(), "lookup_multiscattering (linear sun axis)");
}

TEST(AtmosphereDecode, LookupMultiscatteringTerminatorMapping) {
  ASSERT_EQ(alpha_mie_scene().multiscattering_mapping("multiscattering").sun, SunMapping::terminator);
  multiscattering_case(alpha_mie_scene(), "lookup_multiscattering (terminator sun axis)");
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
      {"lookup_sun_disk_luminance", {"sky_view.glsl"}, "layout(binding = 0) uniform sampler2D lut;",
       "vec4(lookup_sun_disk_luminance(atm, lut, vec3(0.0, 0.0, q0.x), q0.yzw, q1.xyz), 0.0)", {&tex}, 3, "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
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

// ---- Bruneton's 4D table -------------------------------------------------------------

glm::dvec4 scattering_query(const BakedScene& s, const ScatteringShape& shape, size_t i,
                            glm::vec4& q0, glm::vec4& q1) {
  const ViewQuery v = view_query(s.atmosphere, i, kScatteringQueryDim, shape.mu_s_min);
  q0 = glm::vec4(float(v.r), float(v.mu), float(v.mu_s), float(v.nu));
  const bool hits = ray_intersects_ground(s.atmosphere.bottom_radius_m, q0.x, q0.y);
  q1 = glm::vec4(hits ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  return glm::dvec4(q0);
}

TEST(AtmosphereDecode, LookupScatteringSeparateMie) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const ScatteringShape shape = shape_of(s);
  const Texture scattering = s.texture("scattering"), single_mie = s.texture("single_mie");
  const GlTexture t0 = upload_dds(s.dds_path("scattering"), s.sampler("scattering", kClamp));
  const GlTexture t1 = upload_dds(s.dds_path("single_mie"), s.sampler("single_mie", kClamp));
  const Comparison c = run_case(
      {"lookup_scattering (single Mie table)", {"bruneton.glsl"},
       "layout(binding = 0) uniform sampler3D scattering;\n"
       "layout(binding = 1) uniform sampler3D single_mie;\nuniform ScatteringShape shape;",
       "vec4(lookup_scattering(scattering, single_mie, shape, atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       {&t0, &t1}, 3,
       "Texture3D<float4> scattering : register(t0);\nTexture3D<float4> single_mie : register(t1);\n"
       "SamplerState table_sampler : register(s0);\n" "ScatteringShape load_shape() {\n  ScatteringShape s;\n  s.r_size = int(extra(0).x);\n  s.mu_size = int(extra(0).y);\n  s.mu_s_size = int(extra(0).z);\n  s.nu_size = int(extra(0).w);\n  s.mu_s_min = extra(1).x;\n  return s;\n}\n",
       "float4(lookup_scattering(scattering, single_mie, table_sampler, load_shape(), atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       shape_extra(shape)},
      s.parameters("scattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        const glm::dvec4 q = scattering_query(s, shape, i, q0, q1);
        return rgb(lookup_scattering(scattering, single_mie, shape, atm, q.x, q.y, q.z, q.w,
                                     q1.x > 0.5f));
      },
      [&](const ComputeProgram& p) { set_shape(p, shape); });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, LookupScatteringMieInAlpha) {
  const BakedScene& s = alpha_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const ScatteringShape shape = shape_of(s);
  const Texture scattering = s.texture("scattering");
  ASSERT_EQ(scattering.channel_count(), 4);
  const GlTexture t0 = upload_dds(s.dds_path("scattering"), s.sampler("scattering", kClamp));
  const Comparison c = run_case(
      {"lookup_scattering (Mie in alpha)", {"bruneton.glsl"},
       "layout(binding = 0) uniform sampler3D scattering;\nuniform ScatteringShape shape;",
       "vec4(lookup_scattering(scattering, shape, atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       {&t0}, 3,
       "Texture3D<float4> scattering : register(t0);\nSamplerState table_sampler : register(s0);\n" "ScatteringShape load_shape() {\n  ScatteringShape s;\n  s.r_size = int(extra(0).x);\n  s.mu_size = int(extra(0).y);\n  s.mu_s_size = int(extra(0).z);\n  s.nu_size = int(extra(0).w);\n  s.mu_s_min = extra(1).x;\n  return s;\n}\n",
       "float4(lookup_scattering(scattering, table_sampler, load_shape(), atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       shape_extra(shape)},
      s.parameters("scattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        const glm::dvec4 q = scattering_query(s, shape, i, q0, q1);
        return rgb(lookup_scattering(scattering, Texture(), shape, atm, q.x, q.y, q.z, q.w,
                                     q1.x > 0.5f));
      },
      [&](const ComputeProgram& p) { set_shape(p, shape); });
  expect_within(c, kCoordinateBar);
}

// Bruneton 2017 GetSkyRadiance and GetSkyRadianceToPoint composed from the
// C++ lookups the same way (camera moved to the top from space, the
// transmittance between the ends, S(camera) - T S(point)).
struct SkyRadianceCpu {
  const Texture* scattering;
  const Texture* single_mie;  // empty: Mie in alpha
  const Texture* transmittance;
  ScatteringShape shape;
  const Atmosphere* atm;

  // Bruneton 2017 GetSkyRadiance: from space, r = Rt and r mu grows by the
  // distance to the top.
  bool to_top(glm::dvec3& camera, glm::dvec3 view, double& r, double& r_mu) const {
    r = glm::length(camera);
    r_mu = glm::dot(camera, view);
    const double rt = atm->top_radius_m;
    if (r <= rt) return true;
    const double disc = r_mu * r_mu - (r - rt) * (r + rt);
    if (r_mu >= 0.0 || disc < 0.0) return false;
    const double t = -r_mu - std::sqrt(disc);
    camera += t * view;
    r = rt;
    r_mu += t;
    return true;
  }
  glm::dvec3 radiance(glm::dvec3 camera, glm::dvec3 view, glm::dvec3 sun) const {
    double r, r_mu;
    if (!to_top(camera, view, r, r_mu)) return glm::dvec3(0.0);
    const double mu = r_mu / r, mu_s = glm::dot(camera, sun) / r;
    return lookup_scattering(*scattering, *single_mie, shape, *atm, r, mu, mu_s,
                             glm::dot(view, sun), ray_intersects_ground(atm->bottom_radius_m, r, mu));
  }
  glm::dvec3 radiance_to_point(glm::dvec3 camera, glm::dvec3 point, glm::dvec3 sun) const {
    const glm::dvec3 view = glm::normalize(point - camera);
    double r, r_mu;
    if (!to_top(camera, view, r, r_mu)) return glm::dvec3(0.0);
    const double mu = r_mu / r, mu_s = glm::dot(camera, sun) / r;
    const double nu = glm::dot(view, sun), d = glm::length(point - camera);
    const bool hits = ray_intersects_ground(atm->bottom_radius_m, r, mu);
    const glm::dvec3 T = lookup_transmittance(*transmittance, *atm, r, mu, d, hits);
    const double r_p = std::clamp(radius_after(r, mu, d), atm->bottom_radius_m, atm->top_radius_m);
    const double mu_p = (r * mu + d) / r_p, mu_s_p = (r * mu_s + d * nu) / r_p;
    return lookup_scattering(*scattering, *single_mie, shape, *atm, r, mu, mu_s, nu, hits) -
           T * lookup_scattering(*scattering, *single_mie, shape, *atm, r_p, mu_p, mu_s_p, nu, hits);
  }
};

// A camera from the ground to 300 km (space), a view and a sun uniform on
// the sphere, and a point along the view inside the atmosphere.
void camera_query(const Atmosphere& atm, size_t i, glm::vec4& q0, glm::vec4& q1, glm::vec4& point) {
  auto dir = [&](uint32_t d) {
    const double z = 2.0 * unit(i, d) - 1.0, phi = 2.0 * kPi * unit(i, d + 1);
    const double s = std::sqrt(1.0 - z * z);
    return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
  };
  const double altitude = 300e3 * unit(i, 140) * unit(i, 140);
  glm::vec3 view = dir(141);
  const glm::vec3 sun = dir(143);
  q0 = glm::vec4(float(atm.bottom_radius_m + altitude), view);
  q1 = glm::vec4(sun, 0.0f);
  const glm::dvec3 camera(0.0, 0.0, double(q0.x));
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, camera, glm::dvec3(view));
  if (span.hits_atmosphere && span.t_exit - span.t_enter < 1.0) {
    // A camera on the ground looking into it has no segment: look up.
    view = glm::vec3(0.0f, 0.0f, 1.0f);
    q0 = glm::vec4(q0.x, view);
    span = clip_ray_to_atmosphere(atm, camera, glm::dvec3(view));
  }
  const double d = span.hits_atmosphere
                       ? span.t_enter + (0.02 + 0.98 * unit(i, 145)) * (span.t_exit - span.t_enter)
                       : 1e3;
  point = glm::vec4(glm::vec3(camera + d * glm::dvec3(view)), 0.0f);
}

void sky_radiance_case(const BakedScene& s, bool separate, bool to_point) {
  const Atmosphere& atm = s.atmosphere;
  const ScatteringShape shape = shape_of(s);
  const Texture scattering = s.texture("scattering"), tlut = s.texture("transmittance");
  const Texture single_mie = separate ? s.texture("single_mie") : Texture();
  const GlTexture t0 = upload_dds(s.dds_path("scattering"), s.sampler("scattering", kClamp));
  const GlTexture t1 = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const GlTexture t2 = upload_dds(s.dds_path(separate ? "single_mie" : "scattering"),
                                  s.sampler(separate ? "single_mie" : "scattering", kClamp));
  const SkyRadianceCpu cpu{&scattering, &single_mie, &tlut, shape, &atm};
  const std::string mie = separate ? "scattering, single_mie, " : "scattering, ";
  const std::string call =
      to_point ? "sky_radiance_to_point(" + mie + "lut, shape, atm, vec3(0.0, 0.0, q0.x), "
                                                  "points[i].xyz, q1.xyz, T)"
               : "sky_radiance(" + mie + "lut, shape, atm, vec3(0.0, 0.0, q0.x), q0.yzw, q1.xyz, T)";
  std::vector<glm::vec4> points(kQueries);
  const std::string what = std::string(to_point ? "sky_radiance_to_point" : "sky_radiance") +
                           (separate ? " (single Mie table)" : " (Mie in alpha)");
  std::vector<glm::vec4> q0s(kQueries), q1s(kQueries);
  for (size_t i = 0; i < kQueries; ++i) camera_query(atm, i, q0s[i], q1s[i], points[i]);
  const StorageBuffer point_data(points);
  point_data.bind(2);
  point_data.bind(10);  // the HLSL twin's t10
  const std::string hlsl_mie = separate ? "scattering, single_mie, s, " : "scattering, s, ";
  const std::string hlsl_call =
      to_point ? "sky_radiance_to_point(" + hlsl_mie +
                     "lut, s, load_shape(), atm, float3(0.0, 0.0, q0.x), points[i].xyz, q1.xyz, T)"
               : "sky_radiance(" + hlsl_mie +
                     "lut, s, load_shape(), atm, float3(0.0, 0.0, q0.x), q0.yzw, q1.xyz, T)";
  const Comparison c = run_case(
      {what, {"bruneton.glsl"},
       "layout(binding = 0) uniform sampler3D scattering;\n"
       "layout(binding = 1) uniform sampler2D lut;\n"
       "layout(binding = 2) uniform sampler3D single_mie;\n"
       "layout(std430, binding = 2) readonly buffer Points { vec4 points[]; };\n"
       "uniform ScatteringShape shape;\n"
       "vec3 radiance(int i, vec4 q0, vec4 q1) { vec3 T; return " + call + "; }",
       "vec4(radiance(i, q0, q1), 0.0)", {&t0, &t1, &t2}, 3,
       "Texture3D<float4> scattering : register(t0);\nTexture2D<float4> lut : register(t1);\n"
       "Texture3D<float4> single_mie : register(t2);\nSamplerState s : register(s0);\n"
       "StructuredBuffer<float4> points : register(t10);\n"
       "ScatteringShape load_shape() {\n  ScatteringShape sh;\n  sh.r_size = int(extra(0).x);\n"
       "  sh.mu_size = int(extra(0).y);\n  sh.mu_s_size = int(extra(0).z);\n"
       "  sh.nu_size = int(extra(0).w);\n  sh.mu_s_min = extra(1).x;\n  return sh;\n}\n"
       "float3 radiance(int i, float4 q0, float4 q1, AtmosphereParameters atm) {\n"
       "  float3 T;\n  return " + hlsl_call + ";\n}\n",
       "float4(radiance(i, q0, q1, atm), 0.0)", shape_extra(shape)},
      s.parameters("scattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        q0 = q0s[i];
        q1 = q1s[i];
        const glm::dvec3 camera(0.0, 0.0, double(q0.x)), sun = glm::dvec3(glm::vec3(q1));
        return rgb(to_point ? cpu.radiance_to_point(camera, glm::dvec3(glm::vec3(points[i])), sun)
                            : cpu.radiance(camera, glm::dvec3(q0.y, q0.z, q0.w), sun));
      },
      [&](const ComputeProgram& p) { set_shape(p, shape); });
  if (to_point)
    expect_within(c, kDifferenceBar, kDifferenceRmsBar);
  else
    expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, SkyRadiance) {
  sky_radiance_case(separate_mie_scene(), true, false);
  sky_radiance_case(alpha_mie_scene(), false, false);
}

TEST(AtmosphereDecode, SkyRadianceToPoint) {
  sky_radiance_case(separate_mie_scene(), true, true);
  sky_radiance_case(alpha_mie_scene(), false, true);
}

TEST(AtmosphereDecode, LookupIrradiance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture table = s.texture("irradiance");
  const GlTexture tex = upload_dds(s.dds_path("irradiance"), s.sampler("irradiance", kClamp));
  const double mu_s_min = s.meta_number("scattering", "mu_s_min");
  const Comparison c = run_case(
      {"lookup_irradiance", {"bruneton.glsl"}, "layout(binding = 0) uniform sampler2D table;",
       "vec4(lookup_irradiance(table, atm, q0.x, q0.y), 0.0)", {&tex}, 3, "Texture2D<float4> table : register(t0);\nSamplerState table_sampler : register(s0);",
       "float4(lookup_irradiance(table, table_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("irradiance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const RadiusCosine p = irradiance_query(atm, i, mu_s_min);
        q0 = glm::vec4(float(p.r), float(p.mu), 0.0f, 0.0f);
        return rgb(lookup_irradiance(table, atm, q0.x, q0.y));
      });
  expect_within(c, kBar);
}

TEST(AtmosphereDecode, ComputeDirectIrradiance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"compute_direct_irradiance", {"bruneton.glsl"}, "layout(binding = 0) uniform sampler2D lut;",
       "vec4(compute_direct_irradiance(atm, lut, q0.x, q0.y), 0.0)", {&tex}, 3, "Texture2D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);",
       "float4(compute_direct_irradiance(atm, lut, lut_sampler, q0.x, q0.y), 0.0)", {}},
      s.parameters("transmittance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const double u = unit(i, 120);
        const double r = atm.bottom_radius_m + (atm.top_radius_m - atm.bottom_radius_m) * u * u;
        q0 = glm::vec4(float(r), float(2.0 * unit(i, 121) - 1.0), 0.0f, 0.0f);
        return rgb(compute_direct_irradiance(atm, lut, q0.x, q0.y));
      });
  expect_within(c, kBar);
}

// ---- The azimuth-free 3D table ----------------------------------------------------------

glm::dvec4 scattering3d_query(const Atmosphere& atm, size_t i, glm::vec4& q0, glm::vec4& q1) {
  const ViewQuery v = view_query(atm, i, kScattering3dQueryDim, kScattering3dMuSMin);
  q0 = glm::vec4(float(v.altitude_m), float(v.mu), float(v.mu_s), float(v.nu));
  const bool hits =
      ray_intersects_ground(atm.bottom_radius_m, atm.bottom_radius_m + double(q0.x), q0.y);
  q1 = glm::vec4(hits ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  return glm::dvec4(q0);
}

void set_shape3d(const ComputeProgram& p, const Texture& t) {
  p.set("shape.height_size", t.width);
  p.set("shape.view_size", t.height);
  p.set("shape.sun_size", t.depth);
}

TEST(AtmosphereDecode, LookupScattering3dMieInAlpha) {
  const BakedScene& s = alpha_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture table = s.texture("scattering3d");
  ASSERT_EQ(table.channel_count(), 4);
  const Scattering3dShape shape{table.width, table.height, table.depth};
  const GlTexture tex = upload_dds(s.dds_path("scattering3d"), s.sampler("scattering3d", kClamp));
  const Comparison c = run_case(
      {"lookup_scattering3d (Mie in alpha)", {"scattering3d.glsl"},
       "layout(binding = 0) uniform sampler3D scattering;\nuniform Scattering3dShape shape;",
       "vec4(lookup_scattering3d(scattering, shape, atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       {&tex}, 3,
       "Texture3D<float4> scattering : register(t0);\nSamplerState table_sampler : register(s0);\n" "Scattering3dShape load_shape3d() {\n  Scattering3dShape s;\n  s.height_size = int(extra(0).x);\n  s.view_size = int(extra(0).y);\n  s.sun_size = int(extra(0).z);\n  return s;\n}\n",
       "float4(lookup_scattering3d(scattering, table_sampler, load_shape3d(), atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       shape3d_extra(table)},
      s.parameters("scattering3d"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        const glm::dvec4 q = scattering3d_query(atm, i, q0, q1);
        return rgb(lookup_scattering3d(table, Texture(), shape, atm, q.x, q.y, q.z, q.w, q1.x > 0.5f));
      },
      [&](const ComputeProgram& p) { set_shape3d(p, table); });
  expect_within(c, kCoordinateBar);
}

// The product writes no file for the separate Mie table of the 3D model, so
// both tables come from the same bake in memory.
TEST(AtmosphereDecode, LookupScattering3dSeparateMie) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  Scattering3dSpec spec;
  spec.height_size = 8;
  spec.view_size = 32;
  spec.sun_size = 8;
  spec.orders = 2;
  spec.combined_mie_alpha = false;
  const Scattering3dTextures baked = bake_scattering3d(atm, s.texture("transmittance"), spec, {});
  const GlTexture t0 = upload_texture(baked.scattering, kClamp);
  const GlTexture t1 = upload_texture(baked.mie, kClamp);
  const Comparison c = run_case(
      {"lookup_scattering3d (Mie table)", {"scattering3d.glsl"},
       "layout(binding = 0) uniform sampler3D scattering;\n"
       "layout(binding = 1) uniform sampler3D mie;\nuniform Scattering3dShape shape;",
       "vec4(lookup_scattering3d(scattering, mie, shape, atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       {&t0, &t1}, 3,
       "Texture3D<float4> scattering : register(t0);\nTexture3D<float4> mie : register(t1);\n"
       "SamplerState table_sampler : register(s0);\n" "Scattering3dShape load_shape3d() {\n  Scattering3dShape s;\n  s.height_size = int(extra(0).x);\n  s.view_size = int(extra(0).y);\n  s.sun_size = int(extra(0).z);\n  return s;\n}\n",
       "float4(lookup_scattering3d(scattering, mie, table_sampler, load_shape3d(), atm, q0.x, q0.y, q0.z, q0.w, q1.x > 0.5), 0.0)",
       shape3d_extra(baked.scattering)},
      s.parameters("scattering3d"),
      [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
        const glm::dvec4 q = scattering3d_query(atm, i, q0, q1);
        return rgb(lookup_scattering3d(baked.scattering, baked.mie, baked.shape, atm, q.x, q.y,
                                       q.z, q.w, q1.x > 0.5f));
      },
      [&](const ComputeProgram& p) { set_shape3d(p, baked.scattering); });
  expect_within(c, kCoordinateBar);
}

TEST(AtmosphereDecode, LookupGathering) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture table = s.texture("gathering_sum");
  const GlTexture tex = upload_dds(s.dds_path("gathering_sum"), s.sampler("gathering_sum", kClamp));
  const Comparison c = run_case(
      {"lookup_gathering", {"scattering3d.glsl"}, "layout(binding = 0) uniform sampler2D table;",
       "vec4(lookup_gathering(table, atm, q0.x, q0.y), 0.0)", {&tex}, 3, "Texture2D<float4> table : register(t0);\nSamplerState table_sampler : register(s0);",
       "float4(lookup_gathering(table, table_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("gathering_sum"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const AltitudeSunCosine p = gathering_query(atm, i);
        q0 = glm::vec4(float(p.h), float(p.mu_s), 0.0f, 0.0f);
        return rgb(lookup_gathering(table, atm, q0.x, q0.y));
      });
  expect_within(c, kCoordinateBar);
}

}  // namespace
}  // namespace skybake::gltest

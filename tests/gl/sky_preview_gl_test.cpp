// The sky previews rendered entirely in GLSL from the LUTs, against the CPU
// sky_preview image skybake wrote (atmosphere/sky_preview.hpp): the ground
// panels from the sky-view LUT, the transmittance LUT (sun disk, ground seen
// through the air) and the aerial-perspective volume over the ground, the
// view from space by the ray march of runtime/glsl/sky_raymarch.glsl; the
// same exposure (the file's exposure_<panel>) and tone curve. Bar: 1% RMS
// of the display values per panel. The ray march itself is also compared
// with integrate_scattered_luminance point by point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_preview.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/error_stats.hpp"
#include "gl/baked_atmosphere.hpp"
#include "io/dds.hpp"
#include "io/texture_file.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/run.hpp"
#include "verify/query_points.hpp"

namespace skybake::gltest {
namespace {

const SamplerState kClamp{Filter::linear, Wrap::clamp_to_edge, Wrap::clamp_to_edge,
                          Wrap::clamp_to_edge};
const SamplerState kRepeatU{Filter::linear, Wrap::repeat, Wrap::clamp_to_edge,
                            Wrap::clamp_to_edge};

// Earth at the shipped LUT sizes, and the preview as EXR (display values
// in float, the exposures in the manifest).
struct PreviewScene {
  BakedScene baked;
  Texture preview;  // one layer per panel
};

const PreviewScene& preview_scene() {
  static const PreviewScene scene = [] {
    PreviewScene s;
    s.baked = bake_scene("gl_preview", R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_preview",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + test::source_path("presets/atmospheres/earth.json").string() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [256, 64], "formats": ["dds"] },
    { "product": "multiscattering", "size": [32, 32], "formats": ["dds"], "precision": "float" },
    { "product": "sky_preview", "size": [320, 180], "formats": ["exr"] }
  ]
})");
    s.preview = read_texture_file(s.baked.folder + "/sky_preview.exr").texture;
    return s;
  }();
  return scene;
}

std::string render_shader() {
  return R"(
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) writeonly buffer Pixels { vec4 pixels[]; };
uniform AtmosphereParameters atm;
uniform AtmosphereMedium medium;
uniform MultiscatteringMapping ms_mapping;
layout(binding = 0) uniform sampler2D transmittance_lut;
layout(binding = 1) uniform sampler2D multiscattering_lut;
layout(binding = 2) uniform sampler2DArray skyview_lut;
layout(binding = 3) uniform sampler3D aerial_lut;
uniform int has_luts;  // 1: ground view with its sky-view layer and froxels; 0: ray march
uniform float aerial_range_m;
uniform ivec2 size;
uniform vec3 position;
uniform vec3 sun_dir;
uniform vec3 cam_forward;
uniform vec3 cam_right;
uniform vec3 cam_up;
uniform float tan_half_fov;
uniform float aspect;
uniform float exposure;

// The preview's camera (aerial_perspective_lut.hpp view_dir_from_screen_uv).
vec3 view_dir_from_screen_uv(vec2 uv) {
  float sx = (2.0 * uv.x - 1.0) * tan_half_fov * aspect;
  float sy = (1.0 - 2.0 * uv.y) * tan_half_fov;
  return normalize(cam_forward + sx * cam_right + sy * cam_up);
}

// The previews' diffuse ground, lit by the sun only.
vec3 ground_luminance(vec3 point) {
  float mu_s = clamp_cosine(dot(normalize(point), sun_dir));
  if (mu_s <= 0.0) return vec3(0.0);
  return atm.ground_albedo / kPi * atm.sun_illuminance * mu_s *
         lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius, mu_s);
}

vec3 luminance_toward(vec3 dir) {
  vec3 L = lookup_sun_disk_luminance(atm, transmittance_lut, position, dir, sun_dir);
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
  if (!span.hits_atmosphere) return L;
  float r = max(length(position), atm.bottom_radius);
  if (has_luts == 1 && r <= atm.top_radius) {
    vec3 up = position / length(position);
    L += lookup_skyview(skyview_lut, 0, atm, r, skyview_direction_from_vectors(up, dir, sun_dir));
    if (span.exits_on_ground) {
      float mu = clamp_cosine(dot(up, dir));
      L += lookup_transmittance(transmittance_lut, atm, r, mu, span.t_exit, true) *
           ground_luminance(position + span.t_exit * dir);
    }
    return L;
  }
  vec3 T;
  return L + integrate_scattered_luminance(atm, medium, transmittance_lut, multiscattering_lut,
                                           ms_mapping, position, dir, sun_dir, 3.0e38, 32, false,
                                           true, T);
}

// sky_preview.hpp: x (1 + x / 16) / (1 + x), clamped to [0, 1].
vec3 tonemap(vec3 x) { return clamp(x * (1.0 + x / 16.0) / (1.0 + x), 0.0, 1.0); }

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  vec2 uv = (vec2(px) + 0.5) / vec2(size);
  vec3 dir = view_dir_from_screen_uv(uv);
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
  vec3 L;
  if (has_luts == 1 && span.hits_atmosphere && span.exits_on_ground && span.t_enter == 0.0 &&
      span.t_exit <= aerial_range_m) {
    // An engine's opaque ground through the froxels (Hillaire 2020 sec. 5.4).
    vec4 ap = lookup_aerial_perspective(aerial_lut, aerial_range_m, uv, span.t_exit);
    L = apply_aerial_perspective(ground_luminance(position + span.t_exit * dir), ap);
  } else {
    L = luminance_toward(dir);
  }
  pixels[px.y * size.x + px.x] = vec4(tonemap(exposure * L), 0.0);
}
)";
}

const std::vector<std::string> kIncludes = {"sky_view.glsl", "sky_raymarch.glsl"};

// One panel as bake_sky_preview renders it (sky_preview.cpp render_panel):
// the same camera, sky-view layer and froxel volume, built here the same way.
double panel_rms(const PreviewScene& scene, const SkyPreviewSpec& spec, int p,
                 const GlTexture& transmittance, const GlTexture& multiscattering,
                 const Texture& t_lut, const Texture& ms_lut) {
  const Atmosphere& atm = scene.baked.atmosphere;
  const SkyPreviewPanel& panel = spec.panels.at(size_t(p));
  const double sun_zenith = (90.0 - panel.sun_elevation_deg) * kDeg;
  SkyCamera camera;
  camera.aspect = double(spec.width) / spec.height;
  camera.vertical_fov_rad = spec.vertical_fov_deg * kDeg;
  Texture skyview, aerial;
  double range = 0.0;
  if (panel.from_space) {
    camera.altitude_m = atm.top_radius_m / std::sin(0.45 * camera.vertical_fov_rad) - atm.bottom_radius_m;
    camera.pitch_rad = -kPi / 2;
    skyview = Texture(1, 2, 1, 1, {"R", "G", "B"});  // unread placeholders
    aerial = Texture(1, 1, 2, 1, {"R", "G", "B", "A"});
  } else {
    camera.altitude_m = std::min(spec.camera_altitude_m, 0.5 * (atm.top_radius_m - atm.bottom_radius_m));
    camera.pitch_rad = spec.camera_pitch_deg * kDeg;
    SkyviewLutSpec sky;
    sky.views = {{camera.altitude_m, sun_zenith}};
    skyview = bake_skyview_lut(atm, t_lut, ms_lut, sky, {});
    AerialPerspectiveSpec ap;
    ap.camera = camera;
    ap.sun_zenith_rad = sun_zenith;
    ap.depth_range_m = std::min(32e3, 2.0 * (atm.top_radius_m - atm.bottom_radius_m));
    aerial = bake_aerial_perspective_lut(atm, t_lut, ms_lut, ap, {});
    range = ap.depth_range_m;
  }
  const GlTexture skyview_tex = upload_texture(skyview, kRepeatU, true);
  const GlTexture aerial_tex = upload_texture(aerial, kClamp);
  const CameraBasis basis = camera_basis(camera);
  const ComputeProgram program = compile_compute(kIncludes, render_shader());
  set_atmosphere_uniform(program, "atm", scene.baked.parameters("transmittance"));
  set_medium_uniform(program, "medium", atm);
  set_mapping_uniform(program, "ms_mapping", scene.baked.multiscattering_mapping("multiscattering"));
  program.set("has_luts", panel.from_space ? 0 : 1);
  if (program.has_uniform("aerial_range_m")) program.set("aerial_range_m", float(range));
  program.set("position", glm::vec3(0.0f, 0.0f, float(atm.bottom_radius_m + camera.altitude_m)));
  program.set("sun_dir", glm::vec3(sun_direction(sun_zenith, 0.0)));
  program.set("cam_forward", glm::vec3(basis.forward));
  program.set("cam_right", glm::vec3(basis.right));
  program.set("cam_up", glm::vec3(basis.up));
  program.set("tan_half_fov", float(std::tan(0.5 * camera.vertical_fov_rad)));
  program.set("aspect", float(camera.aspect));
  const double exposure = scene.baked.meta_number("sky_preview", "exposure_" + std::to_string(p));
  program.set("exposure", float(exposure));
  program.set("size", glm::ivec2(spec.width, spec.height));
  transmittance.bind(0);
  multiscattering.bind(1);
  skyview_tex.bind(2);
  aerial_tex.bind(3);
  StorageBuffer out(size_t(spec.width) * spec.height * 4 * sizeof(float));
  out.bind(1);
  dispatch(program, unsigned((spec.width + 7) / 8), unsigned((spec.height + 7) / 8));
  const std::vector<float> gl = out.read_floats();
  double sum = 0.0, mean = 0.0;
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x)
      for (int c = 0; c < 3; ++c) mean += scene.preview.at(x, y, 0, p, c);
  // A panel that is black on both sides would compare trivially.
  EXPECT_GT(mean / (3.0 * spec.width * spec.height), 0.05) << panel.label;
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double e = gl[(size_t(y) * spec.width + x) * 4 + c] - scene.preview.at(x, y, 0, p, c);
        sum += e * e;
      }
  return std::sqrt(sum / (3.0 * spec.width * spec.height));
}

TEST(SkyPreviewGl, EveryPanelWithinOnePercentRms) {
  const PreviewScene& scene = preview_scene();
  const Texture t_lut = read_dds(scene.baked.dds_path("transmittance")).mips.at(0);
  const Texture ms_lut = read_dds(scene.baked.dds_path("multiscattering")).mips.at(0);
  const GlTexture transmittance = upload_dds(scene.baked.dds_path("transmittance"), kClamp);
  const GlTexture multiscattering = upload_dds(scene.baked.dds_path("multiscattering"), kClamp);
  SkyPreviewSpec spec;  // the product's defaults, at the size of the preset
  spec.width = scene.preview.width;
  spec.height = scene.preview.height;
  ASSERT_EQ(scene.preview.layers, int(spec.panels.size()));
  for (int p = 0; p < int(spec.panels.size()); ++p) {
    const double rms = panel_rms(scene, spec, p, transmittance, multiscattering, t_lut, ms_lut);
    std::printf("[ measured ] sky preview panel %s: RMS %.3g of the display range\n",
                spec.panels[size_t(p)].label.c_str(), rms);
    EXPECT_LE(rms, 0.01) << spec.panels[size_t(p)].label;
  }
}

// The ray march against integrate_scattered_luminance at 1024 rays from
// the ground to space (uniform and quadratic steps, lit ground).
TEST(SkyPreviewGl, RayMarchMatchesTheCpuMarch) {
  const PreviewScene& scene = preview_scene();
  const Atmosphere& atm = scene.baked.atmosphere;
  const Texture t_lut = read_dds(scene.baked.dds_path("transmittance")).mips.at(0);
  const Texture ms_lut = read_dds(scene.baked.dds_path("multiscattering")).mips.at(0);
  const GlTexture transmittance = upload_dds(scene.baked.dds_path("transmittance"), kClamp);
  const GlTexture multiscattering = upload_dds(scene.baked.dds_path("multiscattering"), kClamp);
  const ComputeProgram program = compile_compute(
      {"sky_raymarch.glsl"},
      query_shader("uniform AtmosphereMedium medium;\n"
                   "uniform MultiscatteringMapping ms_mapping;\n"
                   "layout(binding = 0) uniform sampler2D transmittance_lut;\n"
                   "layout(binding = 1) uniform sampler2D multiscattering_lut;\n"
                   "vec3 march(vec4 q0, vec4 q1) {\n"
                   "  vec3 T;\n"
                   "  vec3 L = integrate_scattered_luminance(atm, medium, transmittance_lut,\n"
                   "      multiscattering_lut, ms_mapping, vec3(0.0, 0.0, q0.x), q0.yzw, q1.xyz,\n"
                   "      3.0e38, 32,\n"
                   "      q1.w > 0.5, true, T);\n"
                   "  return L;\n"
                   "}\n",
                   "vec4(march(q0, q1), 0.0)"));
  set_atmosphere_uniform(program, "atm", scene.baked.parameters("transmittance"));
  set_medium_uniform(program, "medium", atm);
  const MultiscatteringMapping mapping = scene.baked.multiscattering_mapping("multiscattering");
  set_mapping_uniform(program, "ms_mapping", mapping);
  transmittance.bind(0);
  multiscattering.bind(1);
  const size_t n = 1024;
  std::vector<glm::vec4> queries(2 * n);
  std::vector<glm::dvec4> cpu(n);
  for (size_t i = 0; i < n; ++i) {
    const double altitude = 200e3 * query_unit(i, 130) * query_unit(i, 130);
    auto dir = [&](uint32_t d) {
      const double z = 2.0 * query_unit(i, d) - 1.0, phi = 2.0 * kPi * query_unit(i, d + 1);
      const double s = std::sqrt(1.0 - z * z);
      return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
    };
    const bool quadratic = query_unit(i, 135) < 0.5;
    queries[2 * i] = glm::vec4(float(atm.bottom_radius_m + altitude), dir(131));
    queries[2 * i + 1] = glm::vec4(dir(133), quadratic ? 1.0f : 0.0f);
    const glm::vec4 q0 = queries[2 * i], q1 = queries[2 * i + 1];
    const ScatteringResult r = integrate_scattered_luminance(
        atm, t_lut, &ms_lut, {0.0, 0.0, double(q0.x)}, glm::dvec3(q0.y, q0.z, q0.w),
        glm::dvec3(q1.x, q1.y, q1.z), INFINITY, 32,
        {quadratic ? StepDistribution::quadratic : StepDistribution::uniform, true});
    cpu[i] = glm::dvec4(r.luminance, 0.0);
  }
  const Comparison c = compare(run_queries(program, queries), cpu, 3);
  print_comparison("integrate_scattered_luminance", c);
  EXPECT_LE(c.stats.max_rel, 5e-4);
  EXPECT_LE(c.stats.rms_rel, 5e-5);
  // The HLSL twin on the same points.
  const ComputeProgram hlsl = compile_compute_hlsl(
      {"sky_raymarch.hlsl"},
      hlsl_query_shader("Texture2D<float4> transmittance_lut : register(t0);\n"
                        "Texture2D<float4> multiscattering_lut : register(t1);\n"
                        "SamplerState s : register(s0);\n" +
                            hlsl_load_medium(1) +
                            hlsl_load_mapping() +
                            "float3 march(float4 q0, float4 q1, AtmosphereParameters atm) {\n"
                            "  float3 T;\n"
                            "  return integrate_scattered_luminance(atm, load_medium(),\n"
                            "      transmittance_lut, s, multiscattering_lut, s, load_mapping(),\n"
                            "      float3(0.0, 0.0, q0.x),\n"
                            "      q0.yzw, q1.xyz, 3.0e38, 32, q1.w > 0.5, true, T);\n"
                            "}\n",
                        "float4(march(q0, q1, atm), 0.0)"));
  std::vector<glm::vec4> hlsl_extra = {mapping_extra(mapping)};
  for (const glm::vec4& v : medium_extra(atm)) hlsl_extra.push_back(v);
  transmittance.bind(0);
  multiscattering.bind(1);
  const Comparison h = compare(run_hlsl_queries(hlsl, scene.baked.parameters("transmittance"),
                                                hlsl_extra, queries),
                               cpu, 3);
  print_comparison("integrate_scattered_luminance [HLSL]", h);
  EXPECT_LE(h.stats.max_rel, 5e-4);
  EXPECT_LE(h.stats.rms_rel, 5e-5);
}

}  // namespace
}  // namespace skybake::gltest

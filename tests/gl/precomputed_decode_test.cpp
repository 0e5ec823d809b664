// The engine-side decode of the precomputed tables (Bruneton's 4D table,
// its sky radiance and ground irradiance, the azimuth-free 3D table and its
// gathering LUT) against the C++ lookups, as atmosphere_decode_test.cpp
// does for the Hillaire tables: each
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

// ---- Bruneton's 4D table -------------------------------------------------------------

glm::dvec4 scattering_query(const BakedScene& s, const ScatteringShape& shape, size_t i,
                            glm::vec4& q0, glm::vec4& q1) {
  const ViewQuery v = view_query(s.atmosphere, i, kScatteringQueryDim, shape.mu_s_min);
  q0 = glm::vec4(float(v.r), float(v.mu), float(v.mu_s), float(v.nu));
  const bool hits = ray_intersects_ground(s.atmosphere.bottom_radius_m, q0.x, q0.y);
  q1 = glm::vec4(hits ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  return glm::dvec4(q0);
}

TEST(PrecomputedDecode, LookupScatteringSeparateMie) {
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

TEST(PrecomputedDecode, LookupScatteringMieInAlpha) {
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

TEST(PrecomputedDecode, SkyRadiance) {
  sky_radiance_case(separate_mie_scene(), true, false);
  sky_radiance_case(alpha_mie_scene(), false, false);
}

TEST(PrecomputedDecode, SkyRadianceToPoint) {
  sky_radiance_case(separate_mie_scene(), true, true);
  sky_radiance_case(alpha_mie_scene(), false, true);
}

TEST(PrecomputedDecode, LookupIrradiance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture table = s.texture("irradiance");
  const GlTexture tex = upload_dds(s.dds_path("irradiance"), s.sampler("irradiance", kClamp));
  const double mu_s_min = s.meta_number("scattering", "mu_s_min");
  const Comparison c = run_case(
      {"lookup_irradiance", {"bruneton.glsl"}, glsl_table2d("table"),
       "vec4(lookup_irradiance(table, atm, q0.x, q0.y), 0.0)", {&tex}, 3, hlsl_table2d("table"),
       "float4(lookup_irradiance(table, table_sampler, atm, q0.x, q0.y), 0.0)", {}},
      s.parameters("irradiance"), [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const RadiusCosine p = irradiance_query(atm, i, mu_s_min);
        q0 = glm::vec4(float(p.r), float(p.mu), 0.0f, 0.0f);
        return rgb(lookup_irradiance(table, atm, q0.x, q0.y));
      });
  expect_within(c, kBar);
}

TEST(PrecomputedDecode, ComputeDirectIrradiance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("transmittance");
  const GlTexture tex = upload_dds(s.dds_path("transmittance"), s.sampler("transmittance", kClamp));
  const Comparison c = run_case(
      {"compute_direct_irradiance", {"bruneton.glsl"}, glsl_table2d("lut"),
       "vec4(compute_direct_irradiance(atm, lut, q0.x, q0.y), 0.0)", {&tex}, 3, hlsl_table2d("lut"),
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

TEST(PrecomputedDecode, LookupScattering3dMieInAlpha) {
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
       "Texture3D<float4> scattering : register(t0);\nSamplerState table_sampler : register(s0);\n"
       + std::string(kHlslLoadShape3d),
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
TEST(PrecomputedDecode, LookupScattering3dSeparateMie) {
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
       "SamplerState table_sampler : register(s0);\n"
       + std::string(kHlslLoadShape3d),
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

TEST(PrecomputedDecode, LookupGathering) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture table = s.texture("gathering_sum");
  const GlTexture tex = upload_dds(s.dds_path("gathering_sum"), s.sampler("gathering_sum", kClamp));
  const Comparison c = run_case(
      {"lookup_gathering", {"scattering3d.glsl"}, glsl_table2d("table"),
       "vec4(lookup_gathering(table, atm, q0.x, q0.y), 0.0)", {&tex}, 3, hlsl_table2d("table"),
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

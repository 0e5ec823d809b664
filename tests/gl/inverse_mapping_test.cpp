// The inverse mappings of the runtime includes (for engines that bake a
// table themselves, e.g. the sky-view LUT every frame), GLSL and HLSL,
// against the C++ inverses at 4096 texture coordinates: the texel centres
// of the table's first rows, then uniform points. The radius relative, the
// cosines and azimuth / 2 pi absolute, and the round trip uv -> parameters
// -> uv in the shader, in texels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <utility>

#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error_stats.hpp"
#include "core/math.hpp"
#include "gl/baked_atmosphere.hpp"

namespace skybake::gltest {
namespace {

constexpr size_t kPoints = 4096;

// Bars: the radius to float32 (a few ulps), the cosines to 5e-5 (the
// terminator mapping's tan near the ends of its range: measured 2.2e-5),
// the round trip to 1e-3 texel; the transmittance table's to 0.05 texel:
// between its first two rows the altitude is below 25 m (rho = H x_r, so
// h = rho^2 / 2 Rb), and a float radius resolves 0.5 m there (measured
// 0.034 texel at v = 0.032).
constexpr double kRadiusBar = 1e-6, kCosineBar = 5e-5, kRoundTripBar = 1e-3;
constexpr double kTransmittanceRoundTripBar = 0.05;
// The precomputed tables' round trips go through float cosines: near
// mu = +-1 (straight down or up) the cosine moves as x^2 along the axis, so
// float32 resolves about sqrt(6e-8) of it there (measured 0.071 texel on
// the 4D table above its lowest tenth of radii, where the float radius of
// the transmittance case also enters).
constexpr double kPrecomputedRoundTripBar = 0.1;
// The multiple-scattering table's quadratic altitude axis near the ground:
// a float radius holds the altitude to half an ulp (0.25 m at Earth's
// radius), and x_h = sqrt(h / H) moves by up to sqrt(half ulp / H) there
// (0.024 texel at 16 rows over 100 km), the terminator mapping's centre
// mu_h ~ -sqrt(2 h / Rb) by up to sqrt(2 half ulp / Rb) (2.8e-4): bars
// from these on top of the others (quadratic_altitude_bars).

// One inverse: `body` is the text of `VEC4 inverse(VEC4 q0, VEC4 q1,
// AtmosphereParameters atm)` returning (r, cosine, cosine or azimuth / 2 pi,
// round trip in texels), q0 = (u, v, width, height); VEC2..VEC4 and MAPPING
// become the language's types and the multiple-scattering mapping.
struct InverseCase {
  InverseCase(std::string what_, std::string include_, std::string body_, int width_ = 0,
              int height_ = 0, float layer_radius_ = 0.0f,
              const MultiscatteringMapping* mapping_ = nullptr,
              double round_trip_bar_ = kRoundTripBar)
      : what(std::move(what_)), include(std::move(include_)), body(std::move(body_)),
        width(width_), height(height_), layer_radius(layer_radius_), mapping(mapping_),
        round_trip_bar(round_trip_bar_) {}
  std::string what, include, body;
  int width = 0, height = 0;
  float layer_radius = 0;  // q1.x
  const MultiscatteringMapping* mapping = nullptr;
  double round_trip_bar = kRoundTripBar;
  double cosine_bar = kCosineBar;
  // Optional: fills q0, q1 of point i (default: point() and the table's size).
  std::function<void(size_t, glm::vec4&, glm::vec4&)> make_query;
  std::string declarations;           // GLSL (uniforms); the HLSL reads extra(1..)
  std::string hlsl_declarations;
  std::vector<glm::vec4> hlsl_extra;  // after the mapping's extra(0)
  std::function<void(const ComputeProgram&)> uniforms;
};

std::string language(std::string text, bool hlsl) {
  const std::pair<const char*, const char*> words[] = {
      {"VEC2", hlsl ? "float2" : "vec2"}, {"VEC3", hlsl ? "float3" : "vec3"},
      {"VEC4", hlsl ? "float4" : "vec4"}, {"MAPPING", hlsl ? "load_mapping()" : "mapping"},
      {"MAKE_DIRECTION", hlsl ? "make_skyview_direction" : "SkyviewDirection"},
      {"SHAPE3D", hlsl ? "load_shape3d()" : "shape3d"},
      {"SHAPE", hlsl ? "load_shape()" : "shape"}};
  for (const auto& [from, to] : words)
    for (size_t p; (p = text.find(from)) != std::string::npos;) text.replace(p, strlen(from), to);
  return text;
}

// uv at the texel centres of the first rows, then uniform between the
// first and last texel centres (the border half texels map to the ends of
// the ranges, so no round trip comes back there).
glm::vec2 point(size_t i, int width, int height) {
  const size_t centres = size_t(width) * size_t(std::min(height, 8));
  if (i < centres)
    return {float((double(i % size_t(width)) + 0.5) / width),
            float((double(i / size_t(width)) + 0.5) / height)};
  return {float(texel_coord_from_unit(query_unit(i, 150), width)),
          float(texel_coord_from_unit(query_unit(i, 151), height))};
}

void run_inverse(const InverseCase& c, const GlAtmosphere& atm,
                 const std::function<glm::dvec4(const glm::vec4&, const glm::vec4&)>& cpu_of) {
  std::vector<glm::vec4> queries(2 * kPoints, glm::vec4(0.0f));
  std::vector<glm::dvec4> cpu(kPoints);
  for (size_t i = 0; i < kPoints; ++i) {
    if (c.make_query) {
      c.make_query(i, queries[2 * i], queries[2 * i + 1]);
    } else {
      queries[2 * i] = glm::vec4(point(i, c.width, c.height), float(c.width), float(c.height));
      queries[2 * i + 1] = glm::vec4(c.layer_radius, 0.0f, 0.0f, 0.0f);
    }
    cpu[i] = cpu_of(queries[2 * i], queries[2 * i + 1]);
  }
  const std::string function = "VEC4 inverse(VEC4 q0, VEC4 q1, AtmosphereParameters atm) {\n" + c.body + "}\n";
  // Only the multiple-scattering cases declare a mapping.
  const std::string glsl_mapping = c.mapping ? "uniform MultiscatteringMapping mapping;\n" : "";
  const std::string hlsl_mapping =
      c.mapping ? hlsl_load_mapping() : "";
  const ComputeProgram glsl = compile_compute(
      {c.include + ".glsl"},
      query_shader(glsl_mapping + c.declarations + language(function, false), "inverse(q0, q1, atm)"));
  set_atmosphere_uniform(glsl, "atm", atm);
  const MultiscatteringMapping linear;
  if (c.mapping && glsl.has_uniform("mapping.sun")) set_mapping_uniform(glsl, "mapping", *c.mapping);
  if (c.uniforms) c.uniforms(glsl);
  const ComputeProgram hlsl = compile_compute_hlsl(
      {c.include + ".hlsl"},
      hlsl_query_shader(hlsl_mapping + c.hlsl_declarations + language(function, true),
                        "inverse(q0, q1, atm)"));
  std::vector<glm::vec4> extra = {mapping_extra(c.mapping ? *c.mapping : linear)};
  extra.insert(extra.end(), c.hlsl_extra.begin(), c.hlsl_extra.end());
  const std::pair<std::string, std::vector<glm::vec4>> runs[] = {
      {"", run_queries(glsl, queries)}, {" [HLSL]", run_hlsl_queries(hlsl, atm, extra, queries)}};
  for (const auto& [name, gl] : runs) {
    double r_rel = 0, cosine = 0, round_trip = 0;
    glm::vec4 worst_uv(0.0f);
    for (size_t i = 0; i < kPoints; ++i) {
      r_rel = std::max(r_rel, std::abs(gl[i].x - cpu[i].x) / std::abs(cpu[i].x));
      cosine = std::max({cosine, std::abs(gl[i].y - cpu[i].y), std::abs(gl[i].z - cpu[i].z)});
      if (gl[i].w > round_trip) worst_uv = queries[2 * i];
      round_trip = std::max(round_trip, double(gl[i].w));
      if (!std::isfinite(gl[i].x + gl[i].y + gl[i].z + gl[i].w)) r_rel = INFINITY;
    }
    std::printf("[ measured ] %s%s: r %.3g relative, cosines %.3g, round trip %.3g texels "
                "(worst at q0 %.6f, %.6f, %.6f, %.6f)\n",
                c.what.c_str(), name.c_str(), r_rel, cosine, round_trip, worst_uv.x, worst_uv.y, worst_uv.z, worst_uv.w);
    EXPECT_LE(r_rel, kRadiusBar) << c.what << name;
    EXPECT_LE(cosine, c.cosine_bar) << c.what << name;
    EXPECT_LE(round_trip, c.round_trip_bar) << c.what << name;
  }
}

std::vector<int> dimensions(const BakedScene& s, const std::string& output) {
  return s.entry(output).at("dimensions").get<std::vector<int>>();
}

TEST(InverseMapping, Transmittance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const std::vector<int> n = dimensions(s, "transmittance");
  run_inverse({"r_mu_from_transmittance_uv", "transmittance", R"(
  float r, mu;
  r_mu_from_transmittance_uv(atm, q0.xy, int(q0.z), int(q0.w), r, mu);
  VEC2 uv = transmittance_uv_from_r_mu(atm, r, mu, int(q0.z), int(q0.w));
  return VEC4(r, mu, 0.0, max(abs(uv.x - q0.x) * q0.z, abs(uv.y - q0.y) * q0.w));
)", n.at(0), n.at(1), 0.0f, nullptr, kTransmittanceRoundTripBar},
              s.parameters("transmittance"), [&](const glm::vec4& q0, const glm::vec4&) {
                const glm::vec2 uv(q0);
                double r = 0, mu = 0;
                r_mu_from_transmittance_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), r, mu);
                return glm::dvec4(r, mu, 0.0, 0.0);
              });
}

void quadratic_altitude_bars(InverseCase& c, const Atmosphere& atm, int height) {
  const float rb = float(atm.bottom_radius_m);
  const double half_ulp = 0.5 * double(std::nextafter(rb, INFINITY) - rb);
  const double thickness = atm.top_radius_m - atm.bottom_radius_m;
  c.round_trip_bar = kRoundTripBar + (height - 1) * std::sqrt(half_ulp / thickness);
  c.cosine_bar = kCosineBar + std::sqrt(2.0 * half_ulp / atm.bottom_radius_m);
}

void multiscattering_inverse(const BakedScene& s, const std::string& what) {
  const Atmosphere& atm = s.atmosphere;
  const std::vector<int> n = dimensions(s, "multiscattering");
  const MultiscatteringMapping mapping = s.multiscattering_mapping("multiscattering");
  InverseCase c{what, "multiscattering", R"(
  VEC2 p = r_mu_s_from_multiscattering_uv(atm, q0.xy, int(q0.z), int(q0.w), MAPPING);
  VEC2 uv = multiscattering_uv_from_r_mu_s(atm, p.x, p.y, int(q0.z), int(q0.w), MAPPING);
  return VEC4(p.x, p.y, 0.0, max(abs(uv.x - q0.x) * q0.z, abs(uv.y - q0.y) * q0.w));
)", n.at(0), n.at(1)};
  c.mapping = &mapping;
  if (mapping.altitude == AltitudeMapping::quadratic) quadratic_altitude_bars(c, atm, n.at(1));
  run_inverse(c, s.parameters("multiscattering"), [&](const glm::vec4& q0, const glm::vec4&) {
                const glm::vec2 uv(q0);
    const RadiusSunCosine p =
        r_mu_s_from_multiscattering_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), mapping);
    return glm::dvec4(p.r, p.mu_s, 0.0, 0.0);
  });
}

TEST(InverseMapping, Multiscattering) {
  multiscattering_inverse(separate_mie_scene(), "r_mu_s_from_multiscattering_uv (linear)");
  multiscattering_inverse(alpha_mie_scene(), "r_mu_s_from_multiscattering_uv (terminator, quadratic altitude)");
}

TEST(InverseMapping, Skyview) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const std::vector<int> n = dimensions(s, "skyview");
  for (const double altitude : {200.0, 5000.0, 150e3}) {
    InverseCase c{"view_from_skyview_uv at " + std::to_string(int(altitude)) + " m", "sky_view", R"(
  SkyviewDirection v = view_from_skyview_uv(atm, q1.x, q0.xy, int(q0.z), int(q0.w));
  VEC2 uv = skyview_uv_from_view(atm, q1.x, v, int(q0.z), int(q0.w));
  // The azimuth wraps: the round trip in u is taken modulo 1.
  float du = abs(uv.x - q0.x);
  du = min(du, 1.0 - du);
  VEC3 w = skyview_vector_from_direction(v);
  return VEC4(q1.x + 0.0 * w.x, v.mu, v.azimuth / (2.0 * kPi), max(du * q0.z, abs(uv.y - q0.y) * q0.w));
)", n.at(0), n.at(1)};
    c.layer_radius = float(atm.bottom_radius_m + altitude);
    run_inverse(c, s.parameters("skyview"), [&](const glm::vec4& q0, const glm::vec4&) {
                const glm::vec2 uv(q0);
      const SkyviewDirection v = view_from_skyview_uv(atm, double(c.layer_radius), glm::dvec2(uv),
                                                      n.at(0), n.at(1));
      return glm::dvec4(double(c.layer_radius), v.mu, v.azimuth_rad / (2.0 * kPi), 0.0);
    });
  }
}

TEST(InverseMapping, Irradiance) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const std::vector<int> n = dimensions(s, "irradiance");
  run_inverse({"r_mu_s_from_irradiance_uv", "bruneton", R"(
  float r, mu_s;
  r_mu_s_from_irradiance_uv(atm, q0.xy, int(q0.z), int(q0.w), r, mu_s);
  VEC2 uv = irradiance_uv_from_r_mu_s(atm, r, mu_s, int(q0.z), int(q0.w));
  return VEC4(r, mu_s, 0.0, max(abs(uv.x - q0.x) * q0.z, abs(uv.y - q0.y) * q0.w));
)", n.at(0), n.at(1)},
              s.parameters("irradiance"), [&](const glm::vec4& q0, const glm::vec4&) {
                const glm::vec2 uv(q0);
                double r = 0, mu_s = 0;
                r_mu_s_from_irradiance_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), r, mu_s);
                return glm::dvec4(r, mu_s, 0.0, 0.0);
              });
}

// A coordinate between the first and last texel centres of a half axis of
// n texels: the ground half (below 0.5) or the sky half.
float half_axis(double x, bool lower, int n) {
  const double c = texel_coord_from_unit(x, n / 2);
  return float(lower ? 0.5 - 0.5 * c : 0.5 + 0.5 * c);
}

TEST(InverseMapping, Scattering4d) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  ScatteringShape shape;
  shape.r_size = int(s.meta_number("scattering", "r_size"));
  shape.mu_size = int(s.meta_number("scattering", "mu_size"));
  shape.mu_s_size = int(s.meta_number("scattering", "mu_s_size"));
  shape.nu_size = int(s.meta_number("scattering", "nu_size"));
  shape.mu_s_min = s.meta_number("scattering", "mu_s_min");
  InverseCase c{"r_mu_mu_s_nu_from_scattering_uvwz", "bruneton", R"(
  float r, mu, mu_s, nu;
  bool hits;
  r_mu_mu_s_nu_from_scattering_uvwz(atm, SHAPE, q0, r, mu, mu_s, nu, hits);
  VEC4 back = scattering_uvwz_from_r_mu_mu_s_nu(atm, SHAPE, r, mu, mu_s, nu, hits);
  VEC4 d = abs(back - q0) * VEC4(float(SHAPE.nu_size - 1), float(SHAPE.mu_s_size),
                                 float(SHAPE.mu_size), float(SHAPE.r_size));
  return VEC4(r, mu, mu_s, max(max(d.x, d.y), max(d.z, d.w)));
)"};
  c.make_query = [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
    q0 = glm::vec4(float(query_unit(i, 160)),
                   float(texel_coord_from_unit(query_unit(i, 161), shape.mu_s_size)),
                   half_axis(query_unit(i, 162), query_unit(i, 163) < 0.5, shape.mu_size),
                   float(texel_coord_from_unit(0.1 + 0.9 * query_unit(i, 164), shape.r_size)));
    q1 = glm::vec4(0.0f);
  };
  c.declarations = "uniform ScatteringShape shape;\n";
  c.hlsl_declarations =
      "ScatteringShape load_shape() {\n  ScatteringShape sh;\n  sh.r_size = int(extra(1).x);\n"
      "  sh.mu_size = int(extra(1).y);\n  sh.mu_s_size = int(extra(1).z);\n"
      "  sh.nu_size = int(extra(1).w);\n  sh.mu_s_min = extra(2).x;\n  return sh;\n}\n";
  c.hlsl_extra = {glm::vec4(float(shape.r_size), float(shape.mu_size), float(shape.mu_s_size),
                            float(shape.nu_size)),
                  glm::vec4(float(shape.mu_s_min), 0.0f, 0.0f, 0.0f)};
  c.round_trip_bar = kPrecomputedRoundTripBar;
  c.uniforms = [&](const ComputeProgram& p) {
    p.set("shape.r_size", shape.r_size);
    p.set("shape.mu_size", shape.mu_size);
    p.set("shape.mu_s_size", shape.mu_s_size);
    p.set("shape.nu_size", shape.nu_size);
    p.set("shape.mu_s_min", float(shape.mu_s_min));
  };
  run_inverse(c, s.parameters("scattering"), [&](const glm::vec4& q0, const glm::vec4&) {
    const ScatteringParams p = r_mu_mu_s_nu_from_scattering_uvwz(atm, shape, glm::dvec4(q0));
    return glm::dvec4(p.r, p.mu, p.mu_s, 0.0);
  });
}

TEST(InverseMapping, Scattering3d) {
  const BakedScene& s = separate_mie_scene();
  const Atmosphere& atm = s.atmosphere;
  const std::vector<int> n = dimensions(s, "scattering3d");
  const Scattering3dShape shape{n.at(0), n.at(1), n.at(2)};
  InverseCase c{"h_mu_mu_s_from_scattering3d_uvw", "scattering3d", R"(
  float h, mu, mu_s;
  bool hits;
  h_mu_mu_s_from_scattering3d_uvw(atm, SHAPE3D, q0.xyz, h, mu, mu_s, hits);
  VEC3 back = scattering3d_uvw_from_h_mu_mu_s(atm, SHAPE3D, h, mu, mu_s, hits);
  VEC3 d = abs(back - q0.xyz) * VEC3(float(SHAPE3D.height_size), float(SHAPE3D.view_size),
                                     float(SHAPE3D.sun_size));
  return VEC4(atm.bottom_radius + h, mu, mu_s, max(d.x, max(d.y, d.z)));
)"};
  c.make_query = [&](size_t i, glm::vec4& q0, glm::vec4& q1) {
    // mu above the first tenth of each half: x^5 of a smaller x is below
    // float32's resolution of the cosine (Bodare & Sandberg eq. 17's 0.2
    // power), which the round trip cannot undo.
    // Eq. 17's halves: x = 0 at the horizon on both sides of v = 0.5.
    const double x = texel_coord_from_unit(0.1 + 0.9 * query_unit(i, 171), shape.view_size / 2);
    q0 = glm::vec4(float(texel_coord_from_unit(query_unit(i, 170), shape.height_size)),
                   float(query_unit(i, 172) < 0.5 ? 0.5 * x : 0.5 + 0.5 * x),
                   float(texel_coord_from_unit(query_unit(i, 173), shape.sun_size)), 0.0f);
    q1 = glm::vec4(0.0f);
  };
  c.declarations = "uniform Scattering3dShape shape3d;\n";
  c.hlsl_declarations =
      "Scattering3dShape load_shape3d() {\n  Scattering3dShape sh;\n"
      "  sh.height_size = int(extra(1).x);\n  sh.view_size = int(extra(1).y);\n"
      "  sh.sun_size = int(extra(1).z);\n  return sh;\n}\n";
  c.hlsl_extra = {glm::vec4(float(shape.height_size), float(shape.view_size),
                            float(shape.sun_size), 0.0f)};
  c.round_trip_bar = kPrecomputedRoundTripBar;
  c.uniforms = [&](const ComputeProgram& p) {
    p.set("shape3d.height_size", shape.height_size);
    p.set("shape3d.view_size", shape.view_size);
    p.set("shape3d.sun_size", shape.sun_size);
  };
  run_inverse(c, s.parameters("scattering3d"), [&](const glm::vec4& q0, const glm::vec4&) {
    const Scattering3dParams p =
        h_mu_mu_s_from_scattering3d_uvw(atm, shape, glm::dvec3(glm::vec3(q0)));
    return glm::dvec4(atm.bottom_radius_m + p.h, p.mu, p.mu_s, 0.0);
  });
}

}  // namespace
}  // namespace skybake::gltest

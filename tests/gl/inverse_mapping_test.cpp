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

#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
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

// One inverse: `body` is the text of `VEC4 inverse(VEC4 q0, VEC4 q1,
// AtmosphereParameters atm)` returning (r, cosine, cosine or azimuth / 2 pi,
// round trip in texels), q0 = (u, v, width, height); VEC2..VEC4 and MAPPING
// become the language's types and the multiple-scattering mapping.
struct InverseCase {
  std::string what, include, body;
  int width = 0, height = 0;
  float layer_radius = 0;  // q1.x
  const MultiscatteringMapping* mapping = nullptr;
  double round_trip_bar = kRoundTripBar;
};

std::string language(std::string text, bool hlsl) {
  const std::pair<const char*, const char*> words[] = {
      {"VEC2", hlsl ? "float2" : "vec2"}, {"VEC3", hlsl ? "float3" : "vec3"},
      {"VEC4", hlsl ? "float4" : "vec4"}, {"MAPPING", hlsl ? "load_mapping()" : "mapping"},
      {"MAKE_DIRECTION", hlsl ? "make_skyview_direction" : "SkyviewDirection"}};
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
                 const std::function<glm::dvec4(glm::vec2)>& cpu_of) {
  std::vector<glm::vec4> queries(2 * kPoints, glm::vec4(0.0f));
  std::vector<glm::dvec4> cpu(kPoints);
  for (size_t i = 0; i < kPoints; ++i) {
    const glm::vec2 uv = point(i, c.width, c.height);
    queries[2 * i] = glm::vec4(uv, float(c.width), float(c.height));
    queries[2 * i + 1] = glm::vec4(c.layer_radius, 0.0f, 0.0f, 0.0f);
    cpu[i] = cpu_of(uv);
  }
  const std::string function = "VEC4 inverse(VEC4 q0, VEC4 q1, AtmosphereParameters atm) {\n" + c.body + "}\n";
  // Only the multiple-scattering cases declare a mapping.
  const std::string glsl_mapping = c.mapping ? "uniform MultiscatteringMapping mapping;\n" : "";
  const std::string hlsl_mapping =
      c.mapping ? "MultiscatteringMapping load_mapping() {\n  MultiscatteringMapping m;\n"
                  "  m.sun = int(extra(0).x);\n  m.width = extra(0).y;\n"
                  "  m.offset = extra(0).z;\n  return m;\n}\n"
                : "";
  const ComputeProgram glsl = compile_compute(
      {c.include + ".glsl"},
      query_shader(glsl_mapping + language(function, false), "inverse(q0, q1, atm)"));
  set_atmosphere_uniform(glsl, "atm", atm);
  const MultiscatteringMapping linear;
  if (c.mapping && glsl.has_uniform("mapping.sun")) set_mapping_uniform(glsl, "mapping", *c.mapping);
  const ComputeProgram hlsl = compile_compute_hlsl(
      {c.include + ".hlsl"},
      hlsl_query_shader(hlsl_mapping + language(function, true), "inverse(q0, q1, atm)"));
  const std::vector<glm::vec4> extra = {mapping_extra(c.mapping ? *c.mapping : linear)};
  const std::pair<std::string, std::vector<glm::vec4>> runs[] = {
      {"", run_queries(glsl, queries)}, {" [HLSL]", run_hlsl_queries(hlsl, atm, extra, queries)}};
  for (const auto& [name, gl] : runs) {
    double r_rel = 0, cosine = 0, round_trip = 0;
    glm::vec2 worst_uv(0.0f);
    for (size_t i = 0; i < kPoints; ++i) {
      r_rel = std::max(r_rel, std::abs(gl[i].x - cpu[i].x) / std::abs(cpu[i].x));
      cosine = std::max({cosine, std::abs(gl[i].y - cpu[i].y), std::abs(gl[i].z - cpu[i].z)});
      if (gl[i].w > round_trip) worst_uv = glm::vec2(queries[2 * i]);
      round_trip = std::max(round_trip, double(gl[i].w));
      if (!std::isfinite(gl[i].x + gl[i].y + gl[i].z + gl[i].w)) r_rel = INFINITY;
    }
    std::printf("[ measured ] %s%s: r %.3g relative, cosines %.3g, round trip %.3g texels "
                "(worst at uv %.6f, %.6f)\n",
                c.what.c_str(), name.c_str(), r_rel, cosine, round_trip, worst_uv.x, worst_uv.y);
    EXPECT_LE(r_rel, kRadiusBar) << c.what << name;
    EXPECT_LE(cosine, kCosineBar) << c.what << name;
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
              s.parameters("transmittance"), [&](glm::vec2 uv) {
                double r = 0, mu = 0;
                r_mu_from_transmittance_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), r, mu);
                return glm::dvec4(r, mu, 0.0, 0.0);
              });
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
  run_inverse(c, s.parameters("multiscattering"), [&](glm::vec2 uv) {
    const RadiusSunCosine p =
        r_mu_s_from_multiscattering_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), mapping);
    return glm::dvec4(p.r, p.mu_s, 0.0, 0.0);
  });
}

TEST(InverseMapping, Multiscattering) {
  multiscattering_inverse(separate_mie_scene(), "r_mu_s_from_multiscattering_uv (linear)");
  multiscattering_inverse(alpha_mie_scene(), "r_mu_s_from_multiscattering_uv (terminator)");
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
    run_inverse(c, s.parameters("skyview"), [&](glm::vec2 uv) {
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
              s.parameters("irradiance"), [&](glm::vec2 uv) {
                double r = 0, mu_s = 0;
                r_mu_s_from_irradiance_uv(atm, glm::dvec2(uv), n.at(0), n.at(1), r, mu_s);
                return glm::dvec4(r, mu_s, 0.0, 0.0);
              });
}

}  // namespace
}  // namespace skybake::gltest

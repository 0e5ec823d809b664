// What the decode tests of tests/gl/ share: a decode case (a GLSL function
// call and its HLSL twin, the textures they read), running it at 4096 query
// points against the C++ lookup at the same (float) inputs, the bars, the
// sampler states of docs/runtime.md and the table shapes the shaders are
// told. Header only.
#pragma once

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "atmosphere/scattering_lut.hpp"
#include "core/error_stats.hpp"
#include "gl/baked_atmosphere.hpp"

namespace skybake::gltest {

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
inline Comparison report(const std::string& what, const std::vector<glm::vec4>& queries,
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

inline Comparison run_case(const DecodeCase& c, const GlAtmosphere& atm, const QueryFn& query,
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

inline void expect_within(const Comparison& c, double max_bar, double rms_bar = kRmsBar) {
  EXPECT_LE(c.stats.max_rel, max_bar);
  EXPECT_LE(c.stats.rms_rel, rms_bar);
}

const SamplerState kClamp{Filter::linear, Wrap::clamp_to_edge, Wrap::clamp_to_edge,
                          Wrap::clamp_to_edge};
// The sky-view's azimuth wraps (docs/runtime.md "Sky-view").
const SamplerState kRepeatU{Filter::linear, Wrap::repeat, Wrap::clamp_to_edge,
                            Wrap::clamp_to_edge};

inline double unit(size_t i, uint32_t dim) { return query_unit(i, dim); }

inline glm::dvec4 rgb(glm::dvec3 v) { return glm::dvec4(v, 0.0); }

inline ScatteringShape shape_of(const BakedScene& s) {
  ScatteringShape shape;
  shape.r_size = int(s.meta_number("scattering", "r_size"));
  shape.mu_size = int(s.meta_number("scattering", "mu_size"));
  shape.mu_s_size = int(s.meta_number("scattering", "mu_s_size"));
  shape.nu_size = int(s.meta_number("scattering", "nu_size"));
  shape.mu_s_min = s.meta_number("scattering", "mu_s_min");
  return shape;
}

inline std::vector<glm::vec4> shape_extra(const ScatteringShape& shape) {
  return {glm::vec4(float(shape.r_size), float(shape.mu_size), float(shape.mu_s_size),
                    float(shape.nu_size)),
          glm::vec4(float(shape.mu_s_min), 0.0f, 0.0f, 0.0f)};
}

inline std::vector<glm::vec4> shape3d_extra(const Texture& t) {
  return {glm::vec4(float(t.width), float(t.height), float(t.depth), 0.0f)};
}

// The HLSL twin's Scattering3dShape, from the extra(0) of shape3d_extra.
inline const char* const kHlslLoadShape3d =
    "Scattering3dShape load_shape3d() {\n  Scattering3dShape s;\n"
    "  s.height_size = int(extra(0).x);\n  s.view_size = int(extra(0).y);\n"
    "  s.sun_size = int(extra(0).z);\n  return s;\n}\n";

// One 2D table `name` on unit 0: the GLSL sampler, and the HLSL texture with
// its sampler `<name>_sampler`.
inline std::string glsl_table2d(const std::string& name) {
  return "layout(binding = 0) uniform sampler2D " + name + ";";
}
inline std::string hlsl_table2d(const std::string& name) {
  return "Texture2D<float4> " + name + " : register(t0);\nSamplerState " + name +
         "_sampler : register(s0);";
}

inline void set_shape(const ComputeProgram& p, const ScatteringShape& shape) {
  p.set("shape.r_size", shape.r_size);
  p.set("shape.mu_size", shape.mu_size);
  p.set("shape.mu_s_size", shape.mu_s_size);
  p.set("shape.nu_size", shape.nu_size);
  p.set("shape.mu_s_min", float(shape.mu_s_min));
}

}  // namespace skybake::gltest

// The baked atmosphere the shader tests read: two small presets (Earth's
// atmosphere, every atmosphere product; single Mie in its own table in one,
// in alpha in the other) baked by the real skybake into a scratch folder
// once per process, their manifests, their DDS files decoded for the C++
// lookups, and the helpers that run a decode function at many query points
// on the GL context.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "core/error_stats.hpp"
#include "core/texture.hpp"
#include "gl/gl_context.hpp"

namespace skybake::gltest {

// AtmosphereParameters of runtime/glsl/atmosphere_common.glsl, as floats.
struct GlAtmosphere {
  float bottom_radius = 0, top_radius = 0;
  glm::vec3 sun_illuminance{1.0f};
  float sun_angular_radius = 0;
  glm::vec3 ground_albedo{0.0f}, rayleigh_scattering{0.0f}, mie_scattering{0.0f};
  int mie_phase = 0;  // 0 Cornette-Shanks, 1 Henyey-Greenstein
  float mie_g = 0;
};

// From the preset's atmosphere (scattering_phases for the groups).
GlAtmosphere gl_atmosphere(const Atmosphere& atm);

struct BakedScene {
  std::string folder;      // out/<scene>/
  Atmosphere atmosphere;   // as load_scene read the preset
  nlohmann::json manifest;  // manifest.json

  // The output's manifest entry; fails the test (throws) when absent.
  const nlohmann::json& entry(const std::string& output) const;
  // A metadata value of an output as a number (written as a number or as
  // the string of one).
  double meta_number(const std::string& output, const std::string& key) const;
  std::string dds_path(const std::string& output) const;
  // What an engine reads from the output's manifest metadata: the radii
  // (every table), the Rayleigh and Mie coefficients, Mie phase and g (the
  // precomputed tables), the sun's angular radius (irradiance); what the
  // output does not record comes from the preset (gl_atmosphere).
  GlAtmosphere parameters(const std::string& output) const;
  // The multiple-scattering table's sun axis from its metadata
  // (mu_s_mapping; linear when absent).
  MultiscatteringMapping multiscattering_mapping(const std::string& output) const;
  // The sampler state the output's metadata asks for (filter, wrap_u,
  // wrap_v, wrap_w), or `fallback` when it records none.
  SamplerState sampler(const std::string& output, const SamplerState& fallback) const;
  // The DDS file decoded by our reader (level 0): what the C++ lookups read.
  Texture texture(const std::string& output) const;
};

// Bakes `preset` (a scene named `name`) with the real skybake into
// SKYBAKE_TEST_TMP/gl_scenes/, reused by later test processes while the
// executable and the preset are the same.
BakedScene bake_scene(const std::string& name, const std::string& preset);

// mie "separate": transmittance, multiscattering (linear sun axis), skyview
// (2 layers), aerial_perspective, scattering + single_mie, irradiance,
// scattering3d, gathering_sum. mie "alpha": transmittance, multiscattering
// (terminator sun axis, quadratic altitude axis), scattering, scattering3d.
const BakedScene& separate_mie_scene();
const BakedScene& alpha_mie_scene();

// Sets the uniform struct `name` (AtmosphereParameters of
// runtime/glsl/atmosphere_common.glsl) from an Atmosphere; members the
// program does not use are skipped.
void set_atmosphere_uniform(const ComputeProgram& program, const std::string& name,
                            const GlAtmosphere& atm);

// Sets the uniform struct `name` (AtmosphereMedium of
// runtime/glsl/sky_raymarch.glsl) from the atmosphere's components; throws
// when it has more components or layers than the struct holds.
void set_medium_uniform(const ComputeProgram& program, const std::string& name,
                        const Atmosphere& atm);

// The same medium for the HLSL twin, packed into extra(first ..) values,
// and the HLSL function `AtmosphereMedium load_medium()` that unpacks it.
std::vector<glm::vec4> medium_extra(const Atmosphere& atm);
std::string hlsl_load_medium(int first);

// Sets the uniform struct `name` (MultiscatteringMapping of
// runtime/glsl/multiscattering.glsl), and the same as one extra(k) value
// (sun, width, offset, altitude) for the HLSL twin, which
// hlsl_load_mapping()'s `MultiscatteringMapping load_mapping()` unpacks
// from extra(0).
void set_mapping_uniform(const ComputeProgram& program, const std::string& name,
                         const MultiscatteringMapping& m);
glm::vec4 mapping_extra(const MultiscatteringMapping& m);
std::string hlsl_load_mapping();

// Runs `program` once per query: binding 0 holds the queries (two vec4 each,
// query i at 2i and 2i + 1), binding 1 receives one vec4 per query; the
// uniform `count` holds the number of queries. Local size 64.
std::vector<glm::vec4> run_queries(const ComputeProgram& program,
                                   const std::vector<glm::vec4>& queries);

// The compute shader body run_queries expects around `expression`, a vec4
// of the query's q0 and q1 (vec4 each) and the uniform `atm`, after the
// declarations in `declarations` (samplers, further uniforms).
std::string query_shader(const std::string& declarations, const std::string& expression);

// The HLSL twins: hlsl_query_shader wraps `expression` (a float4 of q0,
// q1 and `atm`, an AtmosphereParameters read from the parameter buffer, and
// extra(k), the case's own float4 values) after `declarations` (textures at
// t0.., samplers at s0..); run_hlsl_queries binds the queries (t8), the
// parameters (t9: the atmosphere, the count, then `extra`) and the results
// (u0) and runs it once per query.
std::string hlsl_query_shader(const std::string& declarations, const std::string& expression);
std::vector<glm::vec4> run_hlsl_queries(const ComputeProgram& program, const GlAtmosphere& atm,
                                        const std::vector<glm::vec4>& extra,
                                        const std::vector<glm::vec4>& queries);

// GL results against C++ references, channel by channel, relative error
// with the floor of core/error_stats.hpp (1e-3 of the largest reference).
struct Comparison {
  ErrorStats stats;
  size_t worst_query = 0;  // the worst, or the first with a value that is not finite
  size_t not_finite = 0;   // NaN or Inf on either side: the comparison fails
};
Comparison compare(const std::vector<glm::vec4>& gl, const std::vector<glm::dvec4>& cpu,
                   int channels);

// Prints "<what>: rms_rel ..., max_rel ... (N queries)" for the report.
void print_comparison(const std::string& what, const Comparison& c);

// The input of a query as the shader receives it (rounded to float), back
// in double for the C++ lookup.
inline double as_float(double v) { return double(float(v)); }

}  // namespace skybake::gltest

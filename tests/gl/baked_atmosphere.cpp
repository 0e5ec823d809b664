#include "gl/baked_atmosphere.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "atmosphere/scattering_lut.hpp"
#include "core/hash.hpp"
#include "io/dds.hpp"
#include "pipeline/preset_loader.hpp"
#include "support/run.hpp"

namespace skybake::gltest {
namespace {

std::string earth_atmosphere_path() {
  return test::source_path("presets/atmospheres/earth.json").string();
}

// Small tables (the decode is what is tested, not the bake's accuracy); a
// few in half precision so RGBA16F uploads are read too.
std::string separate_preset() {
  return R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_separate",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + earth_atmosphere_path() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"], "precision": "half" },
    { "product": "skyview", "size": [48, 27], "formats": ["dds"], "precision": "half",
      "views": [ { "altitude_km": 0.2, "sun_zenith_deg": 30 }, { "altitude_km": 5, "sun_zenith_deg": 88 } ] },
    { "product": "aerial_perspective", "size": [16, 16, 16], "formats": ["dds"], "depth_range_km": 32,
      "camera": { "altitude_km": 0.5, "pitch_deg": -5, "vertical_fov_deg": 60, "aspect": 1.7777777777777777 },
      "sun": { "zenith_deg": 60, "azimuth_deg": 30 } },
    { "product": "scattering", "size": [8, 32, 8, 4], "formats": ["dds"], "orders": 2, "mie": "separate" },
    { "product": "single_mie", "formats": ["dds"] },
    { "product": "irradiance", "size": [16, 4], "formats": ["dds"] },
    { "product": "scattering3d", "size": [8, 32, 8], "formats": ["dds"], "orders": 2, "mie": "separate" },
    { "product": "gathering_sum", "formats": ["dds"] }
  ]
})";
}

std::string alpha_preset() {
  return R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_alpha",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + earth_atmosphere_path() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"], "sun_mapping": "terminator", "altitude_mapping": "quadratic" },
    { "product": "scattering", "size": [8, 32, 8, 4], "formats": ["dds"], "orders": 2, "mie": "alpha", "precision": "half" },
    { "product": "scattering3d", "size": [8, 32, 8], "formats": ["dds"], "orders": 2, "mie": "alpha" }
  ]
})";
}

}  // namespace

BakedScene bake_scene(const std::string& name, const std::string& preset) {
  // One folder per skybake executable, atmosphere file and preset text, kept
  // between test processes: the first process bakes, the next find every
  // output up to date (skybake's own freshness check), so the GL tests, one
  // process each under ctest, do not bake the same scene forty times. A
  // rebuilt executable is a new folder. Bakes of one folder by two
  // processes at once are safe (docs/architecture.md "Files on disk").
  Hasher key;
  key.add(test::read_file(SKYBAKE_EXE));
  key.add(test::read_file(test::source_path("presets/atmospheres/earth.json")));
  key.add(preset);
  const std::filesystem::path dir =
      std::filesystem::path(SKYBAKE_TEST_TMP) / "gl_scenes" / (name + "." + key.hex());
  std::filesystem::create_directories(dir);
  // Folders of earlier executables of this build folder are stale: drop them.
  for (const auto& entry : std::filesystem::directory_iterator(dir.parent_path())) {
    const std::string other = entry.path().filename().string();
    if (other.rfind(name + ".", 0) == 0 && entry.path() != dir) {
      std::error_code ignored;  // another process may be removing it too
      std::filesystem::remove_all(entry.path(), ignored);
    }
  }
  const std::filesystem::path file = dir / (name + ".json");
  {
    const std::filesystem::path temporary = dir / (name + ".json." + std::to_string(getpid()));
    std::ofstream(temporary) << preset;
    std::filesystem::rename(temporary, file);
  }
  const test::RunResult run = test::run_skybake({"bake", file.string(), "-o", (dir / "out").string()});
  if (run.exit_code != 0)
    throw std::runtime_error("skybake bake " + file.string() + " exited " +
                             std::to_string(run.exit_code) + ": " + run.err);
  BakedScene s;
  s.atmosphere = load_scene(file).atmosphere;
  s.folder = (dir / "out" / name).string();
  s.manifest = nlohmann::json::parse(test::read_file(s.folder + "/manifest.json"));
  return s;
}

const nlohmann::json& BakedScene::entry(const std::string& output) const {
  for (const nlohmann::json& e : manifest.at("outputs"))
    if (e.at("name") == output) return e;
  throw std::runtime_error(folder + "/manifest.json lists no output " + output);
}

double BakedScene::meta_number(const std::string& output, const std::string& key) const {
  const nlohmann::json& v = entry(output).at("metadata").at(key);
  return v.is_number() ? v.get<double>() : std::stod(v.get<std::string>());
}

std::string BakedScene::dds_path(const std::string& output) const {
  for (const nlohmann::json& f : entry(output).at("files"))
    if (f.at("format") == "dds") return folder + "/" + f.at("path").get<std::string>();
  throw std::runtime_error(output + " has no DDS file in " + folder);
}

Texture BakedScene::texture(const std::string& output) const {
  return read_dds(dds_path(output)).mips.at(0);
}

const BakedScene& separate_mie_scene() {
  static const BakedScene scene = bake_scene("gl_separate", separate_preset());
  return scene;
}

const BakedScene& alpha_mie_scene() {
  static const BakedScene scene = bake_scene("gl_alpha", alpha_preset());
  return scene;
}

GlAtmosphere gl_atmosphere(const Atmosphere& atm) {
  const ScatteringPhases phases = scattering_phases(atm);
  GlAtmosphere g;
  g.bottom_radius = float(atm.bottom_radius_m);
  g.top_radius = float(atm.top_radius_m);
  g.sun_illuminance = glm::vec3(atm.sun_illuminance);
  g.sun_angular_radius = float(atm.sun_angular_radius_rad);
  g.ground_albedo = glm::vec3(atm.ground_albedo);
  g.rayleigh_scattering = glm::vec3(phases.rayleigh_per_m);
  g.mie_scattering = glm::vec3(phases.mie_per_m);
  g.mie_phase = phases.mie_phase == PhaseKind::henyey_greenstein ? 1 : 0;
  g.mie_g = float(phases.mie_g);
  return g;
}

namespace {

// A metadata vector written as a JSON array or as "a,b,c".
glm::vec3 meta_vec3(const nlohmann::json& v) {
  std::vector<double> x;
  if (v.is_array()) {
    x = v.get<std::vector<double>>();
  } else {
    std::stringstream in(v.get<std::string>());
    std::string item;
    while (std::getline(in, item, ',')) x.push_back(std::stod(item));
  }
  if (x.size() != 3) throw std::runtime_error("expected 3 values, got " + v.dump());
  return glm::vec3(float(x[0]), float(x[1]), float(x[2]));
}

float meta_float(const nlohmann::json& v) {
  return float(v.is_number() ? v.get<double>() : std::stod(v.get<std::string>()));
}

}  // namespace

GlAtmosphere BakedScene::parameters(const std::string& output) const {
  GlAtmosphere g = gl_atmosphere(atmosphere);
  const nlohmann::json& meta = entry(output).at("metadata");
  g.bottom_radius = meta_float(meta.at("bottom_radius_m"));
  g.top_radius = meta_float(meta.at("top_radius_m"));
  if (meta.contains("rayleigh_scattering_per_m"))
    g.rayleigh_scattering = meta_vec3(meta.at("rayleigh_scattering_per_m"));
  if (meta.contains("mie_scattering_per_m")) g.mie_scattering = meta_vec3(meta.at("mie_scattering_per_m"));
  if (meta.contains("mie_g")) g.mie_g = meta_float(meta.at("mie_g"));
  if (meta.contains("mie_phase")) {
    const std::string phase = meta.at("mie_phase").get<std::string>();
    if (phase != "cornette_shanks" && phase != "henyey_greenstein" && phase != "none")
      throw std::runtime_error(output + ": unknown mie_phase " + phase);
    g.mie_phase = phase == "henyey_greenstein" ? 1 : 0;
  }
  if (meta.contains("solar_irradiance")) {
    const nlohmann::json& e = meta.at("solar_irradiance");
    g.sun_illuminance = e.is_number() ? glm::vec3(e.get<float>()) : meta_vec3(e);
  }
  if (meta.contains("sun_angular_radius_rad"))
    g.sun_angular_radius = meta_float(meta.at("sun_angular_radius_rad"));
  return g;
}

MultiscatteringMapping BakedScene::multiscattering_mapping(const std::string& output) const {
  const nlohmann::json& meta = entry(output).at("metadata");
  MultiscatteringMapping m;
  if (meta.contains("altitude_mapping") && meta.at("altitude_mapping") != "linear") {
    if (meta.at("altitude_mapping") != "quadratic")
      throw std::runtime_error(output + ": unknown altitude_mapping " +
                               meta.at("altitude_mapping").dump());
    m.altitude = AltitudeMapping::quadratic;
  }
  if (!meta.contains("mu_s_mapping") || meta.at("mu_s_mapping") == "linear") return m;
  if (meta.at("mu_s_mapping") != "terminator")
    throw std::runtime_error(output + ": unknown mu_s_mapping " + meta.at("mu_s_mapping").dump());
  m.sun = SunMapping::terminator;
  m.width = meta_float(meta.at("mu_s_mapping_width"));
  m.offset = meta_float(meta.at("mu_s_mapping_offset"));
  return m;
}

void set_mapping_uniform(const ComputeProgram& program, const std::string& name,
                         const MultiscatteringMapping& m) {
  const glm::vec4 v = mapping_extra(m);
  program.set(name + ".sun", int(v.x));
  if (program.has_uniform(name + ".width")) program.set(name + ".width", v.y);
  if (program.has_uniform(name + ".offset")) program.set(name + ".offset", v.z);
  if (program.has_uniform(name + ".altitude")) program.set(name + ".altitude", int(v.w));
}

glm::vec4 mapping_extra(const MultiscatteringMapping& m) {
  return {m.sun == SunMapping::terminator ? 1.0f : 0.0f, float(m.width), float(m.offset),
          m.altitude == AltitudeMapping::quadratic ? 1.0f : 0.0f};
}

std::string hlsl_load_mapping() {
  return "MultiscatteringMapping load_mapping() {\n  MultiscatteringMapping m;\n"
         "  m.sun = int(extra(0).x);\n  m.width = extra(0).y;\n  m.offset = extra(0).z;\n"
         "  m.altitude = int(extra(0).w);\n  return m;\n}\n";
}

SamplerState BakedScene::sampler(const std::string& output, const SamplerState& fallback) const {
  const nlohmann::json& meta = entry(output).at("metadata");
  if (!meta.contains("filter")) return fallback;
  auto word = [&](const char* key) { return meta.at(key).get<std::string>(); };
  auto wrap = [&](const char* key, Wrap otherwise) {
    if (!meta.contains(key)) return otherwise;
    const std::string w = word(key);
    if (w == "clamp" || w == "clamp_to_edge") return Wrap::clamp_to_edge;
    if (w == "repeat" || w == "wrap") return Wrap::repeat;
    throw std::runtime_error(output + ": unknown " + key + " " + w);
  };
  const std::string f = word("filter");
  if (f != "linear" && f != "nearest" && f != "point")
    throw std::runtime_error(output + ": unknown filter " + f);
  return {f == "linear" ? Filter::linear : Filter::nearest, wrap("wrap_u", fallback.wrap_s),
          wrap("wrap_v", fallback.wrap_t), wrap("wrap_w", fallback.wrap_r)};
}

void set_atmosphere_uniform(const ComputeProgram& program, const std::string& name,
                            const GlAtmosphere& atm) {
  auto set = [&](const std::string& member, auto v) {
    if (program.has_uniform(name + "." + member)) program.set(name + "." + member, v);
  };
  set("bottom_radius", atm.bottom_radius);
  set("top_radius", atm.top_radius);
  set("sun_illuminance", atm.sun_illuminance);
  set("sun_angular_radius", atm.sun_angular_radius);
  set("ground_albedo", atm.ground_albedo);
  set("rayleigh_scattering", atm.rayleigh_scattering);
  set("mie_scattering", atm.mie_scattering);
  set("mie_phase", atm.mie_phase);
  set("mie_g", atm.mie_g);
}

namespace {

// sky_raymarch.glsl's PHASE_* codes.
int phase_code(PhaseKind phase) {
  return phase == PhaseKind::rayleigh            ? 1
         : phase == PhaseKind::cornette_shanks   ? 2
         : phase == PhaseKind::henyey_greenstein ? 3
                                                 : 0;
}

}  // namespace

void set_medium_uniform(const ComputeProgram& program, const std::string& name,
                        const Atmosphere& atm) {
  constexpr int kMaxComponents = 4, kMaxLayers = 2;  // sky_raymarch.glsl
  if (atm.components.size() > size_t(kMaxComponents))
    throw std::runtime_error("the atmosphere has " + std::to_string(atm.components.size()) +
                             " components, AtmosphereMedium holds " + std::to_string(kMaxComponents));
  auto set_f = [&](const std::string& n, float v) {
    if (program.has_uniform(n)) program.set(n, v);
  };
  auto set_i = [&](const std::string& n, int v) {
    if (program.has_uniform(n)) program.set(n, v);
  };
  set_i(name + ".component_count", int(atm.components.size()));
  for (size_t k = 0; k < atm.components.size(); ++k) {
    const MediumComponent& c = atm.components[k];
    const std::string base = name + ".components[" + std::to_string(k) + "]";
    if (c.density.layers.size() > size_t(kMaxLayers))
      throw std::runtime_error("component " + c.name + " has " +
                               std::to_string(c.density.layers.size()) + " layers, at most " +
                               std::to_string(kMaxLayers) + " fit");
    if (program.has_uniform(base + ".scattering"))
      program.set(base + ".scattering", glm::vec3(c.scattering_per_m));
    if (program.has_uniform(base + ".absorption"))
      program.set(base + ".absorption", glm::vec3(c.absorption_per_m));
    set_i(base + ".phase", phase_code(c.phase));
    set_f(base + ".g", float(c.g));
    set_i(base + ".layer_count", int(c.density.layers.size()));
    for (size_t l = 0; l < c.density.layers.size(); ++l) {
      const DensityLayer& d = c.density.layers[l];
      const std::string lb = base + ".layers[" + std::to_string(l) + "]";
      set_f(lb + ".width", float(d.width_m));
      set_f(lb + ".exp_term", float(d.exp_term));
      set_f(lb + ".exp_scale", float(d.exp_scale_per_m));
      set_f(lb + ".linear_term", float(d.linear_term_per_m));
      set_f(lb + ".constant_term", float(d.constant_term));
    }
  }
}

// Per component 7 values: (scattering, phase), (absorption, g),
// (layer count, 0, 0, 0), then per layer (width, exp_term, exp_scale,
// linear_term), (constant_term, 0, 0, 0); the count first.
std::vector<glm::vec4> medium_extra(const Atmosphere& atm) {
  std::vector<glm::vec4> v = {glm::vec4(float(atm.components.size()), 0.0f, 0.0f, 0.0f)};
  for (const MediumComponent& c : atm.components) {
    v.push_back(glm::vec4(glm::vec3(c.scattering_per_m), float(phase_code(c.phase))));
    v.push_back(glm::vec4(glm::vec3(c.absorption_per_m), float(c.g)));
    v.push_back(glm::vec4(float(c.density.layers.size()), 0.0f, 0.0f, 0.0f));
    for (size_t l = 0; l < 2; ++l) {
      const DensityLayer d = l < c.density.layers.size() ? c.density.layers[l] : DensityLayer{};
      v.push_back(glm::vec4(float(d.width_m), float(d.exp_term), float(d.exp_scale_per_m),
                            float(d.linear_term_per_m)));
      v.push_back(glm::vec4(float(d.constant_term), 0.0f, 0.0f, 0.0f));
    }
  }
  return v;
}

std::string hlsl_load_medium(int first) {
  const std::string f = std::to_string(first);
  return R"(
AtmosphereMedium load_medium() {
  AtmosphereMedium m;
  m.component_count = int(extra()" + f + R"().x);
  for (int k = 0; k < MEDIUM_MAX_COMPONENTS; ++k) {
    int b = )" + f + R"( + 1 + 7 * min(k, max(m.component_count - 1, 0));
    m.components[k].scattering = extra(b).xyz;
    m.components[k].phase = int(extra(b).w);
    m.components[k].absorption = extra(b + 1).xyz;
    m.components[k].g = extra(b + 1).w;
    m.components[k].layer_count = int(extra(b + 2).x);
    for (int l = 0; l < MEDIUM_MAX_LAYERS; ++l) {
      float4 a = extra(b + 3 + 2 * l), c = extra(b + 4 + 2 * l);
      m.components[k].layers[l].width = a.x;
      m.components[k].layers[l].exp_term = a.y;
      m.components[k].layers[l].exp_scale = a.z;
      m.components[k].layers[l].linear_term = a.w;
      m.components[k].layers[l].constant_term = c.x;
    }
  }
  return m;
}
)";
}

std::string query_shader(const std::string& declarations, const std::string& expression) {
  return R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Queries { vec4 queries[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int count;
uniform AtmosphereParameters atm;
)" + declarations + R"(
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= count) return;
  vec4 q0 = queries[2 * i], q1 = queries[2 * i + 1];
  results[i] = )" + expression + R"(;
}
)";
}

std::string hlsl_query_shader(const std::string& declarations, const std::string& expression) {
  return R"(
StructuredBuffer<float4> queries : register(t8);
StructuredBuffer<float4> params : register(t9);
RWStructuredBuffer<float4> results : register(u0);
AtmosphereParameters load_atmosphere() {
  AtmosphereParameters a;
  a.bottom_radius = params[0].x;
  a.top_radius = params[0].y;
  a.sun_angular_radius = params[0].z;
  a.mie_g = params[0].w;
  a.sun_illuminance = params[1].xyz;
  a.mie_phase = int(params[1].w);
  a.ground_albedo = params[2].xyz;
  a.rayleigh_scattering = params[3].xyz;
  a.mie_scattering = params[4].xyz;
  return a;
}
float4 extra(int k) { return params[5 + k]; }
)" + declarations + R"(
[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  int i = int(id.x);
  if (i >= int(params[2].w)) return;
  float4 q0 = queries[2 * i], q1 = queries[2 * i + 1];
  AtmosphereParameters atm = load_atmosphere();
  results[i] = )" + expression + R"(;
}
)";
}

std::vector<glm::vec4> run_hlsl_queries(const ComputeProgram& program, const GlAtmosphere& atm,
                                        const std::vector<glm::vec4>& extra,
                                        const std::vector<glm::vec4>& queries) {
  const size_t n = queries.size() / 2;
  std::vector<glm::vec4> params = {
      {atm.bottom_radius, atm.top_radius, atm.sun_angular_radius, atm.mie_g},
      {atm.sun_illuminance, float(atm.mie_phase)},
      {atm.ground_albedo, float(n)},
      {atm.rayleigh_scattering, 0.0f},
      {atm.mie_scattering, 0.0f}};
  params.insert(params.end(), extra.begin(), extra.end());
  StorageBuffer in(queries), parameters(params);
  StorageBuffer out(std::max<size_t>(n, 1) * sizeof(glm::vec4));
  in.bind(8);
  parameters.bind(9);
  out.bind(0);
  dispatch(program, unsigned((n + 63) / 64));
  const std::vector<float> f = out.read_floats();
  std::vector<glm::vec4> results(n);
  for (size_t i = 0; i < n; ++i) results[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]};
  return results;
}

std::vector<glm::vec4> run_queries(const ComputeProgram& program,
                                   const std::vector<glm::vec4>& queries) {
  const size_t n = queries.size() / 2;
  StorageBuffer in(queries);
  StorageBuffer out(std::max<size_t>(n, 1) * sizeof(glm::vec4));
  in.bind(0);
  out.bind(1);
  program.set("count", int(n));
  dispatch(program, unsigned((n + 63) / 64));
  const std::vector<float> f = out.read_floats();
  std::vector<glm::vec4> results(n);
  for (size_t i = 0; i < n; ++i) results[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]};
  return results;
}

Comparison compare(const std::vector<glm::vec4>& gl, const std::vector<glm::dvec4>& cpu,
                   int channels) {
  Comparison c;
  ErrorTally tally;
  double max_ref = 0.0;
  for (const glm::dvec4& v : cpu)
    for (int k = 0; k < channels; ++k) max_ref = std::max(max_ref, std::abs(v[k]));
  const double floor = kRelativeFloor * max_ref;
  double worst = -1.0;
  size_t not_finite = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    for (int k = 0; k < channels; ++k) {
      if (!std::isfinite(gl[i][k]) || !std::isfinite(cpu[i][k])) {
        if (not_finite++ == 0) c.worst_query = i;
        worst = INFINITY;
        continue;
      }
      tally.add(gl[i][k], cpu[i][k]);
      const double rel = std::abs(gl[i][k] - cpu[i][k]) / std::max(std::abs(cpu[i][k]), floor);
      if (rel > worst && not_finite == 0) {
        worst = rel;
        c.worst_query = i;
      }
    }
  c.stats = tally.stats();
  c.not_finite = not_finite;
  if (not_finite > 0) c.stats.max_rel = c.stats.rms_rel = INFINITY;  // fails every bar
  return c;
}

void print_comparison(const std::string& what, const Comparison& c) {
  std::printf("[ measured ] %s: rms_rel %.3g, max_rel %.3g (max_abs %.3g, %zu values, worst query %zu)\n",
              what.c_str(), c.stats.rms_rel, c.stats.max_rel, c.stats.max_abs, c.stats.samples,
              c.worst_query);
  if (c.not_finite > 0)
    std::printf("             %zu values not finite, the first at query %zu\n", c.not_finite,
                c.worst_query);
}

}  // namespace skybake::gltest

#include "gl/baked_atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "atmosphere/scattering_lut.hpp"
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
    { "product": "scattering", "size": [8, 32, 8, 4], "formats": ["dds"], "orders": 2, "mie": "alpha", "precision": "half" },
    { "product": "scattering3d", "size": [8, 32, 8], "formats": ["dds"], "orders": 2, "mie": "alpha" }
  ]
})";
}

BakedScene bake(const std::string& name, const std::string& preset) {
  const std::filesystem::path dir = test::fresh_dir("gl_" + name);
  const std::filesystem::path file = dir / (name + ".json");
  std::ofstream(file) << preset;
  const test::RunResult run = test::run_skybake({"bake", file.string(), "-o", (dir / "out").string()});
  if (run.exit_code != 0)
    throw std::runtime_error("skybake bake " + file.string() + " exited " +
                             std::to_string(run.exit_code) + ": " + run.err);
  BakedScene s;
  s.atmosphere = load_scene(file).atmosphere;
  s.folder = (dir / "out" / ("gl_" + name)).string();
  s.manifest = nlohmann::json::parse(test::read_file(s.folder + "/manifest.json"));
  return s;
}

}  // namespace

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
  static const BakedScene scene = bake("separate", separate_preset());
  return scene;
}

const BakedScene& alpha_mie_scene() {
  static const BakedScene scene = bake("alpha", alpha_preset());
  return scene;
}

void set_atmosphere_uniform(const ComputeProgram& program, const std::string& name,
                            const Atmosphere& atm) {
  const ScatteringPhases phases = scattering_phases(atm);
  auto set_f = [&](const std::string& member, float v) {
    if (program.has_uniform(name + "." + member)) program.set(name + "." + member, v);
  };
  auto set_v = [&](const std::string& member, glm::dvec3 v) {
    if (program.has_uniform(name + "." + member)) program.set(name + "." + member, glm::vec3(v));
  };
  set_f("bottom_radius", float(atm.bottom_radius_m));
  set_f("top_radius", float(atm.top_radius_m));
  set_v("sun_illuminance", atm.sun_illuminance);
  set_f("sun_angular_radius", float(atm.sun_angular_radius_rad));
  set_v("ground_albedo", atm.ground_albedo);
  set_v("rayleigh_scattering", phases.rayleigh_per_m);
  set_v("mie_scattering", phases.mie_per_m);
  if (program.has_uniform(name + ".mie_phase"))
    program.set(name + ".mie_phase", phases.mie_phase == PhaseKind::henyey_greenstein ? 1 : 0);
  set_f("mie_g", float(phases.mie_g));
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
  for (size_t i = 0; i < cpu.size(); ++i)
    for (int k = 0; k < channels; ++k) {
      tally.add(gl[i][k], cpu[i][k]);
      const double rel = std::abs(gl[i][k] - cpu[i][k]) / std::max(std::abs(cpu[i][k]), floor);
      if (rel > worst) {
        worst = rel;
        c.worst_query = i;
      }
    }
  c.stats = tally.stats();
  return c;
}

void print_comparison(const std::string& what, const Comparison& c) {
  std::printf("[ measured ] %s: rms_rel %.3g, max_rel %.3g (max_abs %.3g, %zu values, worst query %zu)\n",
              what.c_str(), c.stats.rms_rel, c.stats.max_rel, c.stats.max_abs, c.stats.samples,
              c.worst_query);
}

}  // namespace skybake::gltest

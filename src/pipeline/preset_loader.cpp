// Scene preset loading: schema validation (schema_validator.hpp), reference
// inlining, defaults, km -> m conversion and the semantic checks. Each JSON
// subtree carries its Source so that a mistake inside a referenced atmosphere
// file is reported against that file, not the scene that references it.
#include "pipeline/preset_loader.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "core/safe_input.hpp"
#include "core/suggest.hpp"
#include "io/dds.hpp"
#include "pipeline/atmosphere_preset.hpp"
#include "pipeline/spectral_preset.hpp"
#include "pipeline/cloud_products.hpp"
#include "pipeline/output_budget.hpp"
#include "pipeline/output_preset.hpp"
#include "pipeline/preset_source.hpp"
#include "pipeline/product_tables.hpp"
#include "pipeline/schema_validator.hpp"
#include "pipeline/table_conventions.hpp"

namespace skybake {

namespace fs = std::filesystem;
using nlohmann::json;
using preset::Problems;
using preset::Source;
using preset::kMaxSchemaViolations;
using preset::token;
using preset::atmosphere_from;
using preset::check_name_bytes;
using preset::add_components;
using preset::check_scene_budget;
using preset::number;
using preset::output_from;
using preset::rgb;

namespace {

// Keys that never change an output: left out of Scene.resolved (the hash input).
const std::vector<std::string> kNonSemanticKeys = {"$schema", "description"};

// The whole file, or nullopt with the reason in `why`: only a regular file
// within the JSON size limit (core/safe_input.hpp) is read.
std::optional<std::string> read_text(const fs::path& path, std::string& why) {
  FileText read = read_regular_file(path, kMaxJsonFileBytes);
  if (read.status != ReadStatus::ok) {
    why = read.why;
    return std::nullopt;
  }
  return std::move(read.text);
}

// "a scene preset", "an atmosphere preset".
std::string a_preset(const std::string& kind) {
  return (kind.find_first_of("aeiou") == 0 ? "an " : "a ") + kind + " preset";
}

// Refuses a preset of another kind early, with a message that says so.
void check_kind(const json& doc, const std::string& display, const std::string& kind) {
  auto it = doc.find("$schema");
  if (it == doc.end() || !it->is_string()) return;
  const std::string schema = it->get<std::string>();
  for (const char* other : {"scene", "planet", "atmosphere", "clouds"}) {
    const std::string suffix = std::string(other) + ".schema.json";
    const bool names_other =
        schema.size() >= suffix.size() &&
        schema.compare(schema.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (names_other && other != kind)
      throw PresetError(display, "/$schema",
                        fmt::format("this file is {} ({}), expected {}", a_preset(other), schema,
                                    a_preset(kind)));
  }
}

// Parses a preset file's text and checks it holds an object of the right kind.
json parse_preset(const std::string& text, const std::string& display, const std::string& kind) {
  json doc;
  if (auto bad = parse_strict_json(text, doc)) throw PresetError(display, bad->pointer, bad->rule);
  if (doc.is_string() && kind != "scene")
    throw PresetError(display, "",
                      fmt::format("expected an object ({}), got {}; a referenced file "
                                  "cannot reference another file",
                                  a_preset(kind), describe_json(doc)));
  if (!doc.is_object())
    throw PresetError(
        display, "",
        fmt::format("expected an object ({}), got {}", a_preset(kind), describe_json(doc)));
  check_kind(doc, display, kind);
  return doc;
}

// Throws a PresetError listing every violation of `schema` in `doc` (named in
// `src`). `patched`, if given, first receives the document with each
// offending value replaced by one the schema accepts (null when there is
// none), so that the checks of the sections without violations can still run.
void validate(const json& doc, const std::string& schema, const Source& src,
              json* patched = nullptr) {
  const std::vector<SchemaViolation> all =
      validate_against_schema_all(doc, schema, kMaxSchemaViolations, patched);
  if (all.empty()) return;
  std::vector<PresetProblem> problems;
  for (const SchemaViolation& v : all)
    problems.push_back({src.file, src.prefix + v.pointer, v.rule});
  throw PresetError(problems);
}

// The top-level keys of `doc` (and "outputs/<i>" for single outputs) whose
// value `patched` changed: their semantic checks would judge stand-ins.
std::set<std::string> patched_sections(const json& doc, const json& patched) {
  std::set<std::string> changed;
  for (auto& [key, value] : patched.items())
    if (!doc.contains(key) || doc[key] != value) changed.insert(key);
  for (auto& [key, value] : doc.items())
    if (!patched.contains(key)) changed.insert(key);
  if (changed.count("outputs") && doc.contains("outputs") && doc["outputs"].is_array() &&
      patched["outputs"].is_array() && doc["outputs"].size() == patched["outputs"].size()) {
    changed.erase("outputs");
    for (size_t i = 0; i < doc["outputs"].size(); ++i)
      if (doc["outputs"][i] != patched["outputs"][i])
        changed.insert("outputs/" + std::to_string(i));
  }
  return changed;
}

void strip_non_semantic(json& obj) {
  for (const std::string& key : kNonSemanticKeys) obj.erase(key);
}

// Replaces scene[key] (an inline object or the path of a preset file) by the
// object itself; `src` receives where it came from.
void inline_section(json& scene, const std::string& key, const fs::path& scene_file,
                    const std::string& scene_display, Source& src) {
  json& v = scene[key];
  src = Source{scene_display, "/" + key};
  if (v.is_string()) {
    const std::string ref = v.get<std::string>();
    if (ref.empty())
      src.fail("", fmt::format("must not be empty (path of the {} preset file)", key));
    const fs::path path = scene_file.parent_path() / ref;
    const std::string display = path.lexically_normal().string();
    std::string why;
    const std::optional<std::string> text = read_text(path, why);
    if (!text)
      src.fail("", fmt::format("cannot read referenced {} file '{}'{}: {}", key, ref,
                               display == ref ? "" : " (" + display + ")", why));
    json doc = parse_preset(*text, display, key);
    src = Source{display, ""};
    validate(doc, key + ".schema.json", src);
    v = std::move(doc);
  } else if (!v.is_object()) {
    src.fail("", fmt::format("expected an object or a string (path of the {} preset file), got {}",
                             key, describe_json(v)));
  }
  strip_non_semantic(v);
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// A key written in `file` at `pointer` that changes nothing, and why.
PresetProblem no_effect(const std::string& file, const std::string& pointer,
                        const std::string& rule) {
  return {file, pointer, "has no effect: " + rule};
}

bool read_by_an_output(const Scene& scene, const std::string& section) {
  for (const OutputSpec& o : scene.outputs)
    if (contains(find_product(o.product)->scene_sections, section)) return true;
  return false;
}

// The scene's sections and scene-wide keys that no output reads.
void section_warnings(const json& written, const Scene& scene, const std::string& file,
                      const Source& atmosphere_src, std::vector<PresetProblem>& warnings) {
  if (written.contains("clouds") && !read_by_an_output(scene, "clouds"))
    warnings.push_back(no_effect(file, "/clouds",
                                 "no output reads the clouds section (weather, cloud_types, "
                                 "height_gradients and cirrus do)"));
  if (written.contains("atmosphere") && !read_by_an_output(scene, "atmosphere"))
    warnings.push_back(no_effect(
        file, "/atmosphere", "no output reads the planet and atmosphere (the atmosphere tables do)"));
  // The per-wavelength physics is read by a spectral bake only; the RGB
  // coefficients stand for it otherwise.
  if (!written.contains("spectral") && written.contains("atmosphere") &&
      written["atmosphere"].is_object() && written["atmosphere"].contains("spectrum") &&
      read_by_an_output(scene, "atmosphere"))
    warnings.push_back(no_effect(atmosphere_src.file, atmosphere_src.prefix + "/spectrum",
                                 "the scene bakes RGB tables from the atmosphere's RGB "
                                 "coefficients; a \"spectral\" section in the scene (e.g. "
                                 "{\"wavelengths\": 15}) bakes from the spectrum"));
  if (written.contains("convention") &&
      std::none_of(scene.outputs.begin(), scene.outputs.end(),
                   [](const OutputSpec& o) { return takes_convention(o.product); }))
    warnings.push_back(no_effect(file, "/convention",
                                 "no output is a table it lays out (transmittance, "
                                 "multiscattering, skyview, aerial_perspective)"));
}

// Keys written in a valid scene that change nothing (docs/presets.md
// "Keys that have no effect"); `written` is the scene before defaults.
std::vector<PresetProblem> no_effect_warnings(const json& written, const Scene& scene,
                                              const std::string& file,
                                              const Source& atmosphere_src) {
  std::vector<PresetProblem> warnings;
  auto warn = [&](const std::string& pointer, const std::string& rule) {
    warnings.push_back(no_effect(file, pointer, rule));
  };
  section_warnings(written, scene, file, atmosphere_src, warnings);
  for (size_t i = 0; i < scene.outputs.size(); ++i) {
    const json& out = written["outputs"][i];
    const OutputSpec& spec = scene.outputs[i];
    const ProductInfo& info = *find_product(spec.product);
    const std::string at = "/outputs" + token(i);
    const bool exr = contains(spec.formats, "exr"), dds = contains(spec.formats, "dds");
    const bool float_dds = dds && !out.contains("dds_format") && info.default_dds_format.empty();
    const bool ktx2 = contains(spec.formats, "ktx2");
    const bool float_ktx2 =
        ktx2 && !out.contains("ktx2_format") && info.default_dds_format.empty();
    if (out.contains("precision") && !exr && !float_dds && !float_ktx2) {
      const std::string dds_format = out.contains("dds_format")
                                         ? out["dds_format"].get<std::string>()
                                         : info.default_dds_format == "unorm8"
                                               ? "8-bit unorm (the product's default)"
                                               : info.default_dds_format;
      warn(at + "/precision",
           fmt::format("precision sets EXR channels and DDS float formats, and this output "
                       "writes {}",
                       dds ? "no EXR and its DDS in " + dds_format
                           : fmt::format("only {}", fmt::join(spec.formats, ", "))));
    }
    if (out.contains("mips") && !dds && !ktx2)
      warn(at + "/mips", "mips are the DDS mip chain (and KTX2's), and this output writes no DDS "
                         "and no KTX2");
    for (const auto& [key, format] : {std::pair<const char*, const char*>{"exr_compression", "exr"},
                                      {"dds_format", "dds"},
                                      {"dds_header", "dds"},
                                      {"ktx2_format", "ktx2"},
                                      {"grid_names", "vdb"},
                                      {"vdb_compression", "vdb"}})
      if (out.contains(key) && !contains(spec.formats, format))
        warn(at + "/" + key, fmt::format("{} is only used with \"{}\" in formats, and this "
                                         "output writes {}",
                                         key, format, fmt::join(spec.formats, ", ")));
    if (out.contains("max_error") && !info.measure_error)
      warn(at + "/max_error", fmt::format("the bake measures no error of {} (only of atmosphere "
                                          "tables), so max_error has nothing to limit",
                                          info.name));
    if (out.contains("twilight_source") &&
        out.value("radiance_source", std::string()) == "multiscattering_table")
      warn(at + "/twilight_source",
           "twilight_source applies to radiance_source \"converged_field\", and this output "
           "marches with the multiscattering table at every sun");
    if (spec.options.contains("tolerance")) {
      const bool converging = spec.options["tolerance"].get<double>() > 0.0;
      for (const char* key : {"max_orders", "tail"})
        if (out.contains(key) && !converging)
          warn(at + "/" + key,
               fmt::format("{} applies when orders run until they converge (tolerance > 0), and "
                           "tolerance is 0: exactly 'orders' orders are computed",
                           key));
      if (out.contains("orders") && converging)
        warn(at + "/orders",
             "with tolerance > 0 orders run until they converge (up to max_orders), so 'orders' "
             "is not used");
    }
  }
  return warnings;
}

}  // namespace

std::uint64_t output_bytes(const std::vector<int>& size) {
  std::uint64_t bytes = 4 * sizeof(float);
  for (int s : size) {
    const std::uint64_t n = s > 0 ? std::uint64_t(s) : 0;
    if (n != 0 && bytes > std::numeric_limits<std::uint64_t>::max() / n)
      return std::numeric_limits<std::uint64_t>::max();
    bytes *= n;
  }
  return bytes;
}

void check_output_size(const ProductInfo& product, const std::vector<int>& size,
                       const std::string& file, const std::string& pointer) {
  if (size.size() != product.axes.size())
    throw PresetError(
        file, pointer,
        fmt::format("{} has {} axes ({}), got {} size{}", product.name, product.axes.size(),
                    fmt::join(product.axes, ", "), size.size(), size.size() == 1 ? "" : "s"));
  for (size_t k = 0; k < size.size(); ++k) {
    const std::string at = pointer + token(k);
    if (size[k] < 1) throw PresetError(file, at, fmt::format("must be >= 1, got {}", size[k]));
    const std::vector<int>& min_size = product_limits(product.name).min_size;
    if (k < min_size.size() && size[k] < min_size[k])
      throw PresetError(file, at,
                        fmt::format("must be >= {} (smallest {} axis '{}'), got {}", min_size[k],
                                    product.name, product.axes[k], size[k]));
    if (k < product.max_size.size() && size[k] > product.max_size[k])
      throw PresetError(file, at,
                        fmt::format("must be <= {} (largest {} axis '{}'), got {}",
                                    product.max_size[k], product.name, product.axes[k], size[k]));
  }
  const std::uint64_t bytes = output_bytes(size);
  if (bytes > kMaxOutputBytes)
    throw PresetError(
        file, pointer,
        fmt::format("{} texels need {:.1f} GiB at 4 float32 channels, over the {} GiB "
                    "budget of one output",
                    fmt::join(size, "x"), double(bytes) / double(1ull << 30),
                    kMaxOutputBytes >> 30));
}

Scene load_scene(const fs::path& file) {
  const std::string display = file.string();
  std::string why;
  const std::optional<std::string> text = read_text(file, why);
  if (!text) throw IoError(fmt::format("{}: cannot read preset: {}", display, why));
  json doc = parse_preset(*text, display, "scene");
  const Source scene_src{display, ""};
  // Every problem of the scene and the files it references is collected;
  // a section whose schema is broken (in the scene or in its own file) is
  // not checked further, since its values are stand-ins.
  Problems problems;
  std::set<std::string> broken;
  json patched;
  if (!problems.collect([&] { validate(doc, "scene.schema.json", scene_src, &patched); })) {
    if (patched.is_null()) problems.throw_if_any();
    broken = patched_sections(doc, patched);
    doc = std::move(patched);
  }
  if (!broken.count("name"))
    problems.collect([&] { check_name_bytes(doc["name"].get<std::string>(), "", scene_src, "/name"); });

  std::vector<fs::path> sources = {file};
  // Planet and atmosphere come together or not at all (a scene of cloud
  // noise needs neither); products that need them say so below.
  const bool has_planet = doc.contains("planet"), has_atmosphere = doc.contains("atmosphere");
  if (has_planet != has_atmosphere)
    problems.add(scene_src, "",
                 has_planet ? "missing required key 'atmosphere' (a planet needs its "
                              "atmosphere; an empty one is {\"top_radius_km\": ...})"
                            : "missing required key 'planet' (an atmosphere needs its planet)");
  for (const char* key : {"planet", "atmosphere", "clouds"})
    if (doc.contains(key) && doc[key].is_string())
      sources.push_back((file.parent_path() / doc[key].get<std::string>()).lexically_normal());

  Source planet_src, atmosphere_src, clouds_src;
  for (const char* key : {"planet", "atmosphere", "clouds"}) {
    if (!doc.contains(key)) continue;
    Source& src = key[0] == 'p' ? planet_src : key[0] == 'a' ? atmosphere_src : clouds_src;
    if (!problems.collect([&] { inline_section(doc, key, file, display, src); }))
      broken.insert(key);
  }
  // What the preset says before defaults: which keys were written.
  const json written = doc;
  strip_non_semantic(doc);
  apply_schema_defaults(doc, "scene.schema.json");
  // Rules of the clouds section a schema cannot say (ramp order, the rain
  // rule's headroom), named in the file the section came from.
  if (doc.contains("clouds") && !broken.count("clouds"))
    for (const ProductProblem& p : clouds_section_problems(doc["clouds"]))
      problems.add(clouds_src, p.pointer, p.rule);

  Scene scene;
  scene.file = file;
  scene.sources = std::move(sources);
  scene.name = doc["name"].get<std::string>();
  scene.has_atmosphere = has_planet && has_atmosphere;
  if (scene.has_atmosphere && !broken.count("planet") && !broken.count("atmosphere"))
    scene.atmosphere =
        atmosphere_from(doc["planet"], planet_src, doc["atmosphere"], atmosphere_src, problems);

  std::map<std::string, size_t> products, names;
  json& outputs = doc["outputs"];
  if (!broken.count("outputs"))
    for (size_t i = 0; i < outputs.size(); ++i) {
      if (broken.count("outputs/" + std::to_string(i))) continue;
      apply_scene_convention(doc, outputs[i]);
      problems.collect([&] {
        scene.outputs.push_back(output_from(outputs[i], i, display, products, names,
                                            has_planet || has_atmosphere, doc.contains("clouds"),
                                            problems));
      });
    }
  preset::load_spectral(scene, doc, atmosphere_src, scene_src, !broken.count("atmosphere"), problems);
  if (problems.empty())  // every output within its own budgets
    problems.collect([&] { check_scene_budget(scene.outputs, scene_src); });
  problems.throw_if_any();
  scene.warnings = no_effect_warnings(written, scene, display, atmosphere_src);
  scene.resolved = std::move(doc);
  return scene;
}

std::vector<Scene> load_scenes(const std::vector<fs::path>& files) {
  std::vector<Scene> scenes;
  std::map<std::string, fs::path> first_file;  // by scene name
  for (const fs::path& file : files) {
    Scene scene = load_scene(file);
    const auto [it, fresh] = first_file.emplace(scene.name, file);
    std::error_code ec;
    if (!fresh && fs::equivalent(file, it->second, ec)) continue;  // one file named twice
    if (!fresh) throw duplicate_scene_name(file.string(), it->first, it->second.string());
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

PresetError duplicate_scene_name(const std::string& file, const std::string& name,
                                 const std::string& first_file) {
  return PresetError(file, "/name",
                     fmt::format("'{}' is also the name of the scene {}; two scenes of one "
                                 "name would bake into one folder, so rename one",
                                 name, first_file));
}

PresetCheck check_preset(const fs::path& file) {
  const std::string display = file.string();
  std::string why;
  const std::optional<std::string> text = read_text(file, why);
  if (!text) throw IoError(fmt::format("{}: cannot read preset: {}", display, why));
  json doc;
  if (auto bad = parse_strict_json(*text, doc)) throw PresetError(display, bad->pointer, bad->rule);
  PresetCheck check;
  check.kind = "scene";
  if (doc.is_object() && doc.contains("$schema") && doc["$schema"].is_string()) {
    // Only the file name counts: the preset is checked against our own copy.
    const std::string schema = doc["$schema"].get<std::string>();
    const std::string name = schema.substr(schema.find_last_of("/\\") + 1);
    check.kind.clear();
    for (const char* kind : {"scene", "planet", "atmosphere", "clouds"})
      if (name == std::string(kind) + ".schema.json") check.kind = kind;
    if (check.kind.empty())
      throw PresetError(display, "/$schema",
                        fmt::format("expected the schema of a skybake preset (scene, planet, "
                                    "atmosphere or clouds .schema.json), got '{}'",
                                    schema));
  }
  if (check.kind == "scene") {
    const Scene scene = load_scene(file);
    check.scene_name = scene.name;
    check.outputs = scene.outputs.size();
    check.warnings = scene.warnings;
    return check;
  }
  const Source src{display, ""};
  if (!doc.is_object())
    src.fail("", fmt::format("expected an object ({}), got {}", a_preset(check.kind),
                             describe_json(doc)));
  const std::string schema = check.kind + ".schema.json";
  Problems problems;
  if (!problems.collect([&] { validate(doc, schema, src); })) problems.throw_if_any();
  strip_non_semantic(doc);
  apply_schema_defaults(doc, schema);
  if (check.kind == "clouds")
    for (const ProductProblem& p : clouds_section_problems(doc))
      problems.add(src, p.pointer, p.rule);
  if (check.kind == "atmosphere") {
    Atmosphere atmosphere;
    problems.collect([&] {
      number(doc, "top_radius_km", src, "");
      rgb(doc["sun"], "illuminance", src, "/sun");
      number(doc["sun"], "angular_radius_rad", src, "/sun");
    });
    add_components(atmosphere, doc, src, problems);
  }
  if (check.kind == "planet")
    problems.collect([&] {
      number(doc, "radius_km", src, "");
      rgb(doc, "ground_albedo", src, "");
    });
  problems.throw_if_any();
  return check;
}

}  // namespace skybake

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
#include "pipeline/cloud_products.hpp"
#include "pipeline/dds_output.hpp"
#include "pipeline/ktx2_output.hpp"
#include "pipeline/output_budget.hpp"
#include "pipeline/product_tables.hpp"
#include "pipeline/schema_validator.hpp"

namespace skybake {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Output keys every product takes; the rest belong to the product's schema.
const std::vector<std::string> kCommonOutputKeys = {
    "product", "name", "size", "formats", "precision", "dds_format", "ktx2_format", "max_error"};

// Keys that never change an output: left out of Scene.resolved (the hash input).
const std::vector<std::string> kNonSemanticKeys = {"$schema", "description"};

// Output keys of the file writers, which every product takes too.
const std::vector<std::string> kWriterOutputKeys = {"exr_compression", "dds_header",
                                                    "grid_names"};

// Where a JSON subtree came from: the file and the subtree's pointer in it.
struct Source {
  std::string file;
  std::string prefix;

  [[noreturn]] void fail(const std::string& pointer, const std::string& rule) const {
    throw PresetError(file, prefix + pointer, rule);
  }
};

// The problems of one preset and of the files it references, collected so
// that one run reports all of them (PresetError lists the first
// kMaxListedProblems and counts the rest).
class Problems {
 public:
  void add(const Source& src, const std::string& pointer, const std::string& rule) {
    list_.push_back({src.file, src.prefix + pointer, rule});
  }
  // Runs `check`; the problems of a PresetError it throws are kept instead,
  // and false is returned.
  template <typename Check>
  bool collect(Check&& check) {
    try {
      check();
      return true;
    } catch (const PresetError& e) {
      list_.insert(list_.end(), e.problems().begin(), e.problems().end());
      return false;
    }
  }
  bool empty() const { return list_.empty(); }
  size_t size() const { return list_.size(); }
  void throw_if_any() const {
    if (!list_.empty()) throw PresetError(list_);
  }

 private:
  std::vector<PresetProblem> list_;
};

std::string token(const std::string& key) {
  return (json::json_pointer() / key).to_string();
}
std::string token(size_t index) {
  return "/" + std::to_string(index);
}

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

// Schema violations looked for in one document before giving up.
constexpr size_t kMaxSchemaViolations = 100;

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

double number(const json& obj, const std::string& key, const Source& src, const std::string& at) {
  const double x = obj.at(key).get<double>();
  if (!std::isfinite(x)) src.fail(at + token(key), "must be a finite number");
  return x;
}

glm::dvec3 rgb(const json& obj, const std::string& key, const Source& src, const std::string& at) {
  if (!obj.contains(key)) return glm::dvec3(0.0);
  glm::dvec3 c;
  for (int i = 0; i < 3; ++i) {
    c[i] = obj.at(key).at(i).get<double>();
    if (!std::isfinite(c[i]) || c[i] < 0.0)
      src.fail(at + token(key) + token(i), "must be a finite number >= 0");
  }
  return c;
}

DensityProfile density_from(const json& d, const Source& src, const std::string& at) {
  if (d.contains("exponential")) {
    const std::string p = at + "/exponential";
    const double h_km = number(d["exponential"], "scale_height_km", src, p);
    if (!(h_km > 0.0)) src.fail(p + "/scale_height_km", fmt::format("must be > 0, got {}", h_km));
    return exponential_profile(h_km * 1e3);
  }
  if (d.contains("tent")) {
    const std::string p = at + "/tent";
    const double b = number(d["tent"], "bottom_km", src, p);
    const double c = number(d["tent"], "center_km", src, p);
    const double t = number(d["tent"], "top_km", src, p);
    if (!(b < c))
      src.fail(p + "/center_km",
               fmt::format("must be greater than bottom_km ({} <= {})",
                           d["tent"]["center_km"].dump(), d["tent"]["bottom_km"].dump()));
    if (!(c < t))
      src.fail(p + "/top_km",
               fmt::format("must be greater than center_km ({} <= {})", d["tent"]["top_km"].dump(),
                           d["tent"]["center_km"].dump()));
    return tent_profile(b * 1e3, c * 1e3, t * 1e3);
  }
  if (d.contains("uniform")) {
    const std::string p = at + "/uniform";
    const double b = number(d["uniform"], "bottom_km", src, p);
    const double t = number(d["uniform"], "top_km", src, p);
    if (!(b < t))
      src.fail(p + "/top_km",
               fmt::format("must be greater than bottom_km ({} <= {})",
                           d["uniform"]["top_km"].dump(), d["uniform"]["bottom_km"].dump()));
    return uniform_profile(b * 1e3, t * 1e3);
  }
  // "layers": the schema guarantees exactly one form.
  DensityProfile profile;
  const json& layers = d.at("layers");
  for (size_t i = 0; i < layers.size(); ++i) {
    const std::string p = at + "/layers" + token(i);
    DensityLayer l;
    l.width_m = number(layers[i], "width_km", src, p) * 1e3;
    l.exp_term = number(layers[i], "exp_term", src, p);
    l.exp_scale_per_m = number(layers[i], "exp_scale_per_km", src, p) * 1e-3;
    l.linear_term_per_m = number(layers[i], "linear_term_per_km", src, p) * 1e-3;
    l.constant_term = number(layers[i], "constant_term", src, p);
    profile.layers.push_back(l);
  }
  return profile;
}

PhaseKind phase_from(const std::string& name) {
  if (name == "rayleigh") return PhaseKind::rayleigh;
  if (name == "cornette_shanks") return PhaseKind::cornette_shanks;
  if (name == "henyey_greenstein") return PhaseKind::henyey_greenstein;
  return PhaseKind::none;
}

// Adds a component unless its coefficients are all zero (it would cost time
// and change nothing).
void add_component(Atmosphere& atm, MediumComponent c) {
  if (c.scattering_per_m == glm::dvec3(0.0) && c.absorption_per_m == glm::dvec3(0.0)) return;
  atm.components.push_back(std::move(c));
}

MediumComponent component_from(const std::string& name, const json& j, PhaseKind default_phase,
                               const Source& src, const std::string& at) {
  MediumComponent c;
  c.name = name;
  c.scattering_per_m = rgb(j, "scattering_per_m", src, at);
  c.absorption_per_m = rgb(j, "absorption_per_m", src, at);
  c.phase = j.contains("phase") ? phase_from(j["phase"].get<std::string>()) : default_phase;
  c.g = j.contains("g") ? number(j, "g", src, at) : 0.0;
  if (!(c.g > -1.0 && c.g < 1.0))
    src.fail(at + "/g", fmt::format("must be in (-1, 1), got {}", c.g));
  c.density = density_from(j.at("density"), src, at + "/density");
  return c;
}

void check_top_radius(const json& planet, const Source& psrc, const json& atm, const Source& asrc) {
  const double rb = number(planet, "radius_km", psrc, "");
  const double rt = number(atm, "top_radius_km", asrc, "");
  if (rt > rb) return;
  const std::string values = atm["top_radius_km"].dump() + " <= " + planet["radius_km"].dump();
  if (psrc.file == asrc.file)
    asrc.fail("/top_radius_km",
              fmt::format("must be greater than {}/radius_km ({})", psrc.prefix, values));
  asrc.fail("/top_radius_km", fmt::format("must be greater than the planet's radius_km in {} ({})",
                                          psrc.file, values));
}

// The components of `atm` into `a`, each checked on its own.
void add_components(Atmosphere& a, const json& atm, const Source& asrc, Problems& problems) {
  if (atm.contains("rayleigh"))
    problems.collect([&] {
      add_component(
          a, component_from("rayleigh", atm["rayleigh"], PhaseKind::rayleigh, asrc, "/rayleigh"));
    });
  if (atm.contains("mie"))
    problems.collect([&] {
      add_component(a,
                    component_from("mie", atm["mie"], PhaseKind::cornette_shanks, asrc, "/mie"));
    });
  if (atm.contains("ozone"))
    problems.collect([&] {
      add_component(a, component_from("ozone", atm["ozone"], PhaseKind::none, asrc, "/ozone"));
    });
  std::set<std::string> names = {"rayleigh", "mie", "ozone"};
  const json extra = atm.value("extra", json::array());
  for (size_t i = 0; i < extra.size(); ++i)
    problems.collect([&] {
      const std::string at = "/extra" + token(i);
      const std::string name = extra[i]["name"].get<std::string>();
      if (!names.insert(name).second)
        asrc.fail(at + "/name", fmt::format("component name '{}' is already used", name));
      MediumComponent c = component_from(name, extra[i], PhaseKind::none, asrc, at);
      if (c.phase == PhaseKind::none && c.scattering_per_m != glm::dvec3(0.0))
        asrc.fail(at + "/phase",
                  "a component that scatters needs a phase function (scattering_per_m is not "
                  "zero)");
      add_component(a, std::move(c));
    });
}

Atmosphere atmosphere_from(const json& planet, const Source& psrc, const json& atm,
                           const Source& asrc, Problems& problems) {
  problems.collect([&] { check_top_radius(planet, psrc, atm, asrc); });
  Atmosphere a;
  problems.collect([&] {
    a.bottom_radius_m = number(planet, "radius_km", psrc, "") * 1e3;
    a.top_radius_m = number(atm, "top_radius_km", asrc, "") * 1e3;
    a.ground_albedo = rgb(planet, "ground_albedo", psrc, "");
    a.sun_illuminance = rgb(atm["sun"], "illuminance", asrc, "/sun");
    a.sun_angular_radius_rad = number(atm["sun"], "angular_radius_rad", asrc, "/sun");
  });
  add_components(a, atm, asrc, problems);
  return a;
}

// The longest a file or folder name can be on the file systems skybake writes
// to (NAME_MAX); a preset is refused here, not by the first write.
constexpr size_t kMaxFileNameBytes = 255;

// A name becomes a folder or file name: refuses control characters (a NUL
// would cut it short: "ea\0rth" is the folder "ea") and names too long for
// a file system.
void check_name_bytes(const std::string& name, const std::string& longest_suffix,
                      const Source& src, const std::string& pointer) {
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7F)
      src.fail(pointer, fmt::format("must not contain control characters, got U+{:04X} at byte {}",
                                    unsigned(c), i));
  }
  if (name.size() + longest_suffix.size() > kMaxFileNameBytes)
    src.fail(pointer, fmt::format("expected at most {} bytes per file name, got {} for the "
                                  "name{}",
                                  kMaxFileNameBytes, name.size() + longest_suffix.size(),
                                  longest_suffix.empty() ? "" : " and '" + longest_suffix + "'"));
}

std::string gib(std::uint64_t bytes) { return fmt::format("{:.1f} GiB", double(bytes) / double(1ull << 30)); }

// The texture with its layers against the output budget, then the memory its
// bake peaks at against the bake budget (output_budget.hpp).
void check_output_budget(const OutputSpec& spec, const Source& src) {
  const int layers = output_layers(spec);
  const std::uint64_t bytes = output_texture_bytes(spec);
  if (layers > 1 && bytes > kMaxOutputBytes)
    src.fail("/size", fmt::format("{} texels x {} layers ({}) need {} at 4 float32 channels, "
                                  "over the {} GiB budget of one output",
                                  fmt::join(spec.size, "x"), layers,
                                  spec.product == "skyview" ? "one per view" : "one per panel",
                                  gib(bytes), kMaxOutputBytes >> 30));
  const std::uint64_t peak = output_peak_bytes(spec);
  if (peak > kMaxBakeBytes)
    src.fail("/size", fmt::format("baking {} {} ({} at 4 float32 channels) and writing {} takes "
                                  "about {} of memory ({}x its texture), over the {} GiB budget "
                                  "of a bake",
                                  fmt::join(spec.size, "x"), spec.product, gib(bytes),
                                  fmt::join(spec.formats, ", "), gib(peak), working_factor(spec),
                                  kMaxBakeBytes >> 30));
}

// Every texture of a scene stays in memory until the scene is baked; the
// largest bake's working memory comes on top.
void check_scene_budget(const std::vector<OutputSpec>& outputs, const Source& src) {
  std::uint64_t held = 0, extra = 0;
  size_t largest = 0;
  for (size_t i = 0; i < outputs.size(); ++i) {
    // Each output is within the bake budget already, so no sum overflows.
    const std::uint64_t bytes = output_texture_bytes(outputs[i]);
    const std::uint64_t more = output_peak_bytes(outputs[i]) - bytes;
    held += bytes;
    if (more > extra) extra = more, largest = i;
  }
  if (held + extra <= kMaxBakeBytes) return;
  src.fail("/outputs", fmt::format("the textures of the outputs take {} together and stay in "
                                   "memory until the scene is baked; with the {} more that "
                                   "baking {} takes, that is over the {} GiB budget of a bake",
                                   gib(held), gib(extra), outputs[largest].pointer,
                                   kMaxBakeBytes >> 30));
}

// VDB grid names: one per channel of the product's texture (the schema
// checks each name and that they are distinct).
void check_grid_names(const OutputSpec& spec, const Source& src) {
  if (!spec.options.contains("grid_names")) return;
  const size_t names = spec.options["grid_names"].size();
  const int channels = output_channels(spec);
  if (names != size_t(channels))
    src.fail("/grid_names", fmt::format("expected one grid name per channel: {} for {} with these "
                                        "options, got {}",
                                        channels, spec.product, names));
}

std::string to_lower_ascii(std::string s) {
  for (char& ch : s)
    if (ch >= 'A' && ch <= 'Z') ch = char(ch - 'A' + 'a');
  return s;
}

// Checks the product-specific keys of output `out` against the product's
// schema and fills their defaults; false, with the problems in `problems`,
// when they break it.
bool product_options(json& out, const ProductInfo& info, const Source& src, Problems& problems) {
  json options = json::object();
  for (auto& [key, v] : out.items())
    if (std::find(kCommonOutputKeys.begin(), kCommonOutputKeys.end(), key) ==
            kCommonOutputKeys.end() &&
        std::find(kWriterOutputKeys.begin(), kWriterOutputKeys.end(), key) ==
            kWriterOutputKeys.end())
      options[key] = v;
  const std::string schema = "products/" + info.name + ".schema.json";
  const bool has_schema = schema_exists(schema);
  std::vector<std::string> known = kCommonOutputKeys;
  known.insert(known.end(), kWriterOutputKeys.begin(), kWriterOutputKeys.end());
  if (has_schema) {
    for (const std::string& k : schema_property_names(schema)) known.push_back(k);
    const std::vector<SchemaViolation> all =
        validate_against_schema_all(options, schema, kMaxSchemaViolations);
    for (const SchemaViolation& bad : all) {
      if (bad.keyword != "additionalProperties") {
        problems.add(src, bad.pointer, bad.rule);
        continue;
      }
      const std::string key = json::json_pointer(bad.pointer).back();
      problems.add(src, bad.pointer,
                   fmt::format("unknown key '{}'{}", key, did_you_mean(key, known)));
    }
    if (!all.empty()) return false;
    apply_schema_defaults(options, schema);
  } else if (!options.empty()) {
    for (auto& [key, v] : options.items())
      problems.add(src, token(key), fmt::format("unknown key '{}'{} ({} takes no options)", key,
                                                did_you_mean(key, known), info.name));
    return false;
  }
  for (auto& [key, v] : options.items()) out[key] = v;
  return true;
}

OutputSpec output_from(json& out, size_t index, const std::string& file,
                       std::map<std::string, size_t>& products,
                       std::map<std::string, size_t>& names, bool has_atmosphere,
                       bool has_clouds, Problems& problems) {
  OutputSpec spec;
  spec.pointer = "/outputs" + token(index);
  const Source src{file, spec.pointer};
  spec.product = out["product"].get<std::string>();
  const ProductInfo* info = find_product(spec.product);
  if (!info)
    src.fail("/product", fmt::format("unknown product '{}'{}; products: {}", spec.product,
                                     did_you_mean(spec.product, product_names()),
                                     product_names().empty()
                                         ? "none registered"
                                         : fmt::format("{}", fmt::join(product_names(), ", "))));
  const bool options_ok = product_options(out, *info, src, problems);
  const auto& sections = info->scene_sections;
  if (!has_clouds && std::find(sections.begin(), sections.end(), "clouds") != sections.end())
    problems.add(src, "/product",
                 fmt::format("'{}' needs the scene's clouds section (inline or a file of "
                             "presets/clouds/), and this scene has none",
                             info->name));
  if (!has_atmosphere && std::find(sections.begin(), sections.end(), "atmosphere") != sections.end())
    problems.add(src, "/product",
                 fmt::format("'{}' needs the scene's planet and atmosphere, and this scene "
                             "has neither",
                             info->name));

  if (!out.contains("name")) out["name"] = info->name;
  spec.name = out["name"].get<std::string>();
  std::string longest_suffix;
  for (const std::string& format : out.value("formats", info->default_formats)) {
    const std::string suffix = format == "png" ? ".preview.png" : "." + format;
    if (suffix.size() > longest_suffix.size()) longest_suffix = suffix;
  }
  check_name_bytes(spec.name, longest_suffix, src, "/name");
  // Case-insensitive: out/<scene>/Sky.exr and sky.exr are one file on some
  // systems. Checked before the product so that both rules are reachable with
  // one product; a clash of default names hints at the product rule too.
  const auto [clash, fresh] = names.emplace(to_lower_ascii(spec.name), index);
  if (!fresh) {
    const auto earlier = products.find(spec.product);
    const bool same_product = earlier != products.end() && earlier->second == clash->second;
    problems.add(src, "/name",
                 fmt::format("output name '{}' is already used by /outputs/{}{}", spec.name,
                             clash->second,
                             same_product ? " (for the same product: a scene bakes each "
                                            "product at most once)"
                                          : ""));
  }
  if (!products.emplace(spec.product, index).second)
    problems.add(src, "/product",
                 fmt::format("product '{}' is already baked by /outputs/{}; a scene bakes "
                             "each product at most once",
                             spec.product, products[spec.product]));

  if (!out.contains("size")) out["size"] = info->default_size;
  spec.size = out["size"].get<std::vector<int>>();
  const bool size_ok =
      problems.collect([&] { check_output_size(*info, spec.size, file, spec.pointer + "/size"); });

  if (!out.contains("formats")) out["formats"] = info->default_formats;
  spec.formats = out["formats"].get<std::vector<std::string>>();
  for (size_t k = 0; k < spec.formats.size(); ++k) {
    const auto& allowed = info->allowed_formats;
    if (std::find(allowed.begin(), allowed.end(), spec.formats[k]) == allowed.end())
      problems.add(src, "/formats" + token(k),
                   fmt::format("format '{}' is not available for {} (allowed: {})",
                               spec.formats[k], info->name, fmt::join(allowed, ", ")));
  }
  spec.precision = out.value("precision", std::string("float"));
  if (out.contains("exr_compression") &&
      std::find(spec.formats.begin(), spec.formats.end(), "exr") == spec.formats.end())
    problems.add(src, "/exr_compression", "is only used with \"exr\" in formats");
  if (out.contains("dds_format") &&
      std::find(spec.formats.begin(), spec.formats.end(), "dds") == spec.formats.end())
    problems.add(src, "/dds_format", "is only used with \"dds\" in formats");
  if (out.contains("grid_names") &&
      std::find(spec.formats.begin(), spec.formats.end(), "vdb") == spec.formats.end())
    problems.add(src, "/grid_names", "is only used with \"vdb\" in formats");
  if (out.contains("max_error") && !info->measure_error)
    problems.add(src, "/max_error",
                 fmt::format("the bake measures no error of {} (only of atmosphere "
                             "tables), so max_error has nothing to limit",
                             info->name));
  spec.options = out;
  for (const ProductProblem& problem : dds_output_problems(spec, *info))
    problems.add(src, problem.pointer, problem.rule);
  for (const ProductProblem& problem : ktx2_output_problems(spec, *info))
    problems.add(src, problem.pointer, problem.rule);
  if (options_ok) problems.collect([&] { check_grid_names(spec, src); });
  if (size_ok) check_output_budget(spec, src);  // a size already refused is not budgeted
  // Product-specific rules the schema cannot say (e.g. a noise octave finer
  // than two voxels), checked before anything is allocated.
  if (info->check && options_ok && size_ok)
    for (const ProductProblem& problem : info->check(spec))
      problems.add(src, problem.pointer, problem.rule);
  return spec;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// Keys written in a valid scene that change nothing (docs/presets.md
// "Keys that have no effect"); `written` is the scene before defaults.
std::vector<PresetProblem> no_effect_warnings(const json& written, const Scene& scene,
                                              const std::string& file) {
  std::vector<PresetProblem> warnings;
  auto warn = [&](const std::string& pointer, const std::string& rule) {
    warnings.push_back({file, pointer, "has no effect: " + rule});
  };
  auto read_by_an_output = [&](const std::string& section) {
    for (const OutputSpec& o : scene.outputs)
      if (contains(find_product(o.product)->scene_sections, section)) return true;
    return false;
  };
  if (written.contains("clouds") && !read_by_an_output("clouds"))
    warn("/clouds", "no output reads the clouds section (weather, cloud_types, height_gradients "
                    "and cirrus do)");
  if (written.contains("atmosphere") && !read_by_an_output("atmosphere"))
    warn("/atmosphere", "no output reads the planet and atmosphere (the atmosphere tables do)");
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
      problems.collect([&] {
        scene.outputs.push_back(output_from(outputs[i], i, display, products, names,
                                            has_planet || has_atmosphere, doc.contains("clouds"),
                                            problems));
      });
    }
  if (problems.empty())  // every output within its own budgets
    problems.collect([&] { check_scene_budget(scene.outputs, scene_src); });
  problems.throw_if_any();
  scene.warnings = no_effect_warnings(written, scene, display);
  scene.resolved = std::move(doc);
  return scene;
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

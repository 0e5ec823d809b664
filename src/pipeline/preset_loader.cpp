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
#include "pipeline/output_budget.hpp"
#include "pipeline/product_tables.hpp"
#include "pipeline/schema_validator.hpp"

namespace skybake {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Output keys every product takes; the rest belong to the product's schema.
const std::vector<std::string> kCommonOutputKeys = {"product", "name",      "size",
                                                    "formats", "precision", "dds_format"};

// Keys that never change an output: left out of Scene.resolved (the hash input).
const std::vector<std::string> kNonSemanticKeys = {"$schema", "description"};

// Output keys of the file writers, which every product takes too.
const std::vector<std::string> kWriterOutputKeys = {"exr_compression"};

// Where a JSON subtree came from: the file and the subtree's pointer in it.
struct Source {
  std::string file;
  std::string prefix;

  [[noreturn]] void fail(const std::string& pointer, const std::string& rule) const {
    throw PresetError(file, prefix + pointer, rule);
  }
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

void validate(const json& doc, const std::string& schema, const Source& src) {
  if (auto bad = validate_against_schema(doc, schema)) src.fail(bad->pointer, bad->rule);
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

Atmosphere atmosphere_from(const json& planet, const Source& psrc, const json& atm,
                           const Source& asrc) {
  check_top_radius(planet, psrc, atm, asrc);
  Atmosphere a;
  a.bottom_radius_m = number(planet, "radius_km", psrc, "") * 1e3;
  a.top_radius_m = number(atm, "top_radius_km", asrc, "") * 1e3;
  a.ground_albedo = rgb(planet, "ground_albedo", psrc, "");
  a.sun_illuminance = rgb(atm["sun"], "illuminance", asrc, "/sun");
  a.sun_angular_radius_rad = number(atm["sun"], "angular_radius_rad", asrc, "/sun");
  if (atm.contains("rayleigh"))
    add_component(
        a, component_from("rayleigh", atm["rayleigh"], PhaseKind::rayleigh, asrc, "/rayleigh"));
  if (atm.contains("mie"))
    add_component(a, component_from("mie", atm["mie"], PhaseKind::cornette_shanks, asrc, "/mie"));
  if (atm.contains("ozone"))
    add_component(a, component_from("ozone", atm["ozone"], PhaseKind::none, asrc, "/ozone"));
  std::set<std::string> names = {"rayleigh", "mie", "ozone"};
  const json extra = atm.value("extra", json::array());
  for (size_t i = 0; i < extra.size(); ++i) {
    const std::string at = "/extra" + token(i);
    const std::string name = extra[i]["name"].get<std::string>();
    if (!names.insert(name).second)
      asrc.fail(at + "/name", fmt::format("component name '{}' is already used", name));
    MediumComponent c = component_from(name, extra[i], PhaseKind::none, asrc, at);
    if (c.phase == PhaseKind::none && c.scattering_per_m != glm::dvec3(0.0))
      asrc.fail(at + "/phase",
                "a component that scatters needs a phase function (scattering_per_m is not zero)");
    add_component(a, std::move(c));
  }
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

// A DDS format with fewer components than the product's texture has channels.
void check_dds_format(const OutputSpec& spec, const Source& src) {
  if (!spec.options.contains("dds_format")) return;
  const std::string name = spec.options["dds_format"].get<std::string>();
  const int components = dds_component_count(dds_format_from_name(name));
  const int channels = output_channels(spec);
  if (channels > components)
    src.fail("/dds_format", fmt::format("expected a format with at least {} channels ({} has "
                                        "{}), got {} ({} channel{})",
                                        channels, spec.product, channels, name, components,
                                        components == 1 ? "" : "s"));
}

std::string to_lower_ascii(std::string s) {
  for (char& ch : s)
    if (ch >= 'A' && ch <= 'Z') ch = char(ch - 'A' + 'a');
  return s;
}

// Checks the product-specific keys of output `out` against the product's
// schema and fills their defaults.
void product_options(json& out, const ProductInfo& info, const Source& src) {
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
    if (auto bad = validate_against_schema(options, schema)) {
      if (bad->keyword != "additionalProperties") src.fail(bad->pointer, bad->rule);
      const std::string key = json::json_pointer(bad->pointer).back();
      src.fail(bad->pointer, fmt::format("unknown key '{}'{}", key, did_you_mean(key, known)));
    }
    apply_schema_defaults(options, schema);
  } else if (!options.empty()) {
    const std::string key = options.begin().key();
    src.fail(token(key), fmt::format("unknown key '{}'{} ({} takes no options)", key,
                                     did_you_mean(key, known), info.name));
  }
  for (auto& [key, v] : options.items()) out[key] = v;
}

OutputSpec output_from(json& out, size_t index, const std::string& file,
                       std::map<std::string, size_t>& products,
                       std::map<std::string, size_t>& names, bool has_atmosphere,
                       bool has_clouds) {
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
  product_options(out, *info, src);
  const auto& sections = info->scene_sections;
  if (!has_clouds && std::find(sections.begin(), sections.end(), "clouds") != sections.end())
    src.fail("/product", fmt::format("'{}' needs the scene's clouds section (inline or a file of "
                                     "presets/clouds/), and this scene has none",
                                     info->name));
  if (!has_atmosphere && std::find(sections.begin(), sections.end(), "atmosphere") != sections.end())
    src.fail("/product", fmt::format("'{}' needs the scene's planet and atmosphere, and this scene "
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
    src.fail("/name", fmt::format("output name '{}' is already used by /outputs/{}{}", spec.name,
                                  clash->second,
                                  same_product ? " (for the same product: a scene bakes each "
                                                 "product at most once)"
                                               : ""));
  }
  if (!products.emplace(spec.product, index).second)
    src.fail("/product", fmt::format("product '{}' is already baked by /outputs/{}; a scene bakes "
                                     "each product at most once",
                                     spec.product, products[spec.product]));

  if (!out.contains("size")) out["size"] = info->default_size;
  spec.size = out["size"].get<std::vector<int>>();
  check_output_size(*info, spec.size, file, spec.pointer + "/size");

  if (!out.contains("formats")) out["formats"] = info->default_formats;
  spec.formats = out["formats"].get<std::vector<std::string>>();
  for (size_t k = 0; k < spec.formats.size(); ++k) {
    const auto& allowed = info->allowed_formats;
    if (std::find(allowed.begin(), allowed.end(), spec.formats[k]) == allowed.end())
      src.fail("/formats" + token(k),
               fmt::format("format '{}' is not available for {} (allowed: {})", spec.formats[k],
                           info->name, fmt::join(allowed, ", ")));
  }
  spec.precision = out.value("precision", std::string("float"));
  if (out.contains("exr_compression") &&
      std::find(spec.formats.begin(), spec.formats.end(), "exr") == spec.formats.end())
    src.fail("/exr_compression", "is only used with \"exr\" in formats");
  if (out.contains("dds_format") &&
      std::find(spec.formats.begin(), spec.formats.end(), "dds") == spec.formats.end())
    src.fail("/dds_format", "is only used with \"dds\" in formats");
  spec.options = out;
  check_dds_format(spec, src);
  check_output_budget(spec, src);
  // Product-specific rules the schema cannot say (e.g. a noise octave finer
  // than two voxels), checked before anything is allocated.
  if (info->check)
    for (const ProductProblem& problem : info->check(spec)) src.fail(problem.pointer, problem.rule);
  return spec;
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
  validate(doc, "scene.schema.json", scene_src);
  check_name_bytes(doc["name"].get<std::string>(), "", scene_src, "/name");

  std::vector<fs::path> sources = {file};
  // Planet and atmosphere come together or not at all (a scene of cloud
  // noise needs neither); products that need them say so below.
  const bool has_planet = doc.contains("planet"), has_atmosphere = doc.contains("atmosphere");
  if (has_planet != has_atmosphere)
    scene_src.fail("", has_planet ? "missing required key 'atmosphere' (a planet needs its "
                                    "atmosphere; an empty one is {\"top_radius_km\": ...})"
                                  : "missing required key 'planet' (an atmosphere needs its planet)");
  for (const char* key : {"planet", "atmosphere", "clouds"})
    if (doc.contains(key) && doc[key].is_string())
      sources.push_back((file.parent_path() / doc[key].get<std::string>()).lexically_normal());

  Source planet_src, atmosphere_src;
  if (has_planet) {
    inline_section(doc, "planet", file, display, planet_src);
    inline_section(doc, "atmosphere", file, display, atmosphere_src);
  }
  Source clouds_src;
  if (doc.contains("clouds")) inline_section(doc, "clouds", file, display, clouds_src);
  strip_non_semantic(doc);
  apply_schema_defaults(doc, "scene.schema.json");
  // Rules of the clouds section a schema cannot say (ramp order, the rain
  // rule's headroom), named in the file the section came from.
  if (doc.contains("clouds"))
    for (const ProductProblem& p : clouds_section_problems(doc["clouds"]))
      clouds_src.fail(p.pointer, p.rule);

  Scene scene;
  scene.file = file;
  scene.sources = std::move(sources);
  scene.name = doc["name"].get<std::string>();
  scene.has_atmosphere = has_planet;
  if (has_planet)
    scene.atmosphere =
        atmosphere_from(doc["planet"], planet_src, doc["atmosphere"], atmosphere_src);

  std::map<std::string, size_t> products, names;
  json& outputs = doc["outputs"];
  for (size_t i = 0; i < outputs.size(); ++i)
    scene.outputs.push_back(
        output_from(outputs[i], i, display, products, names, scene.has_atmosphere,
                    doc.contains("clouds")));
  check_scene_budget(scene.outputs, scene_src);
  scene.resolved = std::move(doc);
  return scene;
}

}  // namespace skybake

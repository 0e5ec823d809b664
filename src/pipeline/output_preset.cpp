// One output of a scene preset into an OutputSpec: its product's options
// against the product's schema, names, size, formats and the writers' keys,
// the memory budgets (preset_loader.cpp calls it for every output).
#include "pipeline/output_preset.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/suggest.hpp"
#include "pipeline/dds_output.hpp"
#include "pipeline/ktx2_output.hpp"
#include "pipeline/output_budget.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_tables.hpp"
#include "pipeline/schema_validator.hpp"
#include "pipeline/table_conventions.hpp"

namespace skybake::preset {

using nlohmann::json;

namespace {

// Output keys every product takes; the rest belong to the product's schema.
const std::vector<std::string> kCommonOutputKeys = {
    "product", "name", "size", "formats", "precision", "dds_format", "ktx2_format", "max_error"};

// Output keys of the file writers, which every product takes too.
const std::vector<std::string> kWriterOutputKeys = {"exr_compression", "dds_header",
                                                    "grid_names", "vdb_compression"};

}  // namespace

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

namespace {

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

}  // namespace

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

namespace {

// VDB grid names: one per channel of the product's texture (the schema
// checks each name and that they are distinct).
void check_grid_names(const OutputSpec& spec, const Source& src) {
  const bool vdb = std::find(spec.formats.begin(), spec.formats.end(), "vdb") != spec.formats.end();
  if (!spec.options.contains("grid_names") || !vdb) return;  // without VDB: a warning
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

}  // namespace

namespace {

// The scene sections the product reads must be there.
void check_sections(const ProductInfo& info, bool has_atmosphere, bool has_clouds,
                    const Source& src, Problems& problems) {
  const auto& sections = info.scene_sections;
  if (!has_clouds && std::find(sections.begin(), sections.end(), "clouds") != sections.end())
    problems.add(src, "/product",
                 fmt::format("'{}' needs the scene's clouds section (inline or a file of "
                             "presets/clouds/), and this scene has none",
                             info.name));
  if (!has_atmosphere && std::find(sections.begin(), sections.end(), "atmosphere") != sections.end())
    problems.add(src, "/product",
                 fmt::format("'{}' needs the scene's planet and atmosphere, and this scene "
                             "has neither",
                             info.name));
}

// The output's name (a file name, unique in the scene whatever the case)
// and its product (baked once per scene).
void check_name_and_product(json& out, const ProductInfo& info, OutputSpec& spec, size_t index,
                            std::map<std::string, size_t>& products,
                            std::map<std::string, size_t>& names, const Source& src,
                            Problems& problems) {
  if (!out.contains("name")) out["name"] = info.name;
  spec.name = out["name"].get<std::string>();
  std::string longest_suffix;
  for (const std::string& format : out.value("formats", info.default_formats)) {
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
}

// The formats the product allows, and the writers' keys only with their format.
void check_formats(json& out, const ProductInfo& info, OutputSpec& spec, const Source& src,
                   Problems& problems) {
  if (!out.contains("formats")) out["formats"] = info.default_formats;
  spec.formats = out["formats"].get<std::vector<std::string>>();
  for (size_t k = 0; k < spec.formats.size(); ++k) {
    const auto& allowed = info.allowed_formats;
    if (std::find(allowed.begin(), allowed.end(), spec.formats[k]) == allowed.end())
      problems.add(src, "/formats" + token(k),
                   fmt::format("format '{}' is not available for {} (allowed: {})",
                               spec.formats[k], info.name, fmt::join(allowed, ", ")));
  }
  // A format's key without the format, and max_error on a product whose
  // error is not measured, change nothing: warnings (preset_loader.cpp).
}

}  // namespace

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
  check_sections(*info, has_atmosphere, has_clouds, src, problems);
  check_name_and_product(out, *info, spec, index, products, names, src, problems);

  if (!out.contains("size")) out["size"] = info->default_size;
  spec.size = out["size"].get<std::vector<int>>();
  const bool size_ok =
      problems.collect([&] { check_output_size(*info, spec.size, file, spec.pointer + "/size"); });
  check_formats(out, *info, spec, src, problems);
  spec.precision = out.value("precision", std::string("float"));
  spec.options = out;
  normalize_convention(spec);
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
  if (options_ok && size_ok)
    for (const ProductProblem& problem : convention_problems(spec))
      problems.add(src, problem.pointer, problem.rule);
  return spec;
}

}  // namespace skybake::preset

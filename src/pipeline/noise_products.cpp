// Cloud noise products (docs/reference.md, "Cloud noise"): the Perlin-Worley
// shape volume, the Worley detail volume and curl noise, with their
// parameters in the output object
// (schemas/products/noise_*.schema.json, curl.schema.json). Their spec
// validation (noise/noise_volume.hpp spec_problems) runs at preset load.
#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "noise/curl_texture.hpp"
#include "noise/noise_volume.hpp"
#include "noise/perlin_worley.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/product_options.hpp"
#include "pipeline/product_tables.hpp"

namespace skybake {

namespace {

// The fBm a problem's field names, where it names one: "perlin",
// "perlin_worley", "worley[i]" of the volumes, "octaves" of curl.
std::optional<WorleyFbmSpec> fbm_of(const NoiseShapeSpec& s, const std::string& field) {
  if (field == "perlin") return WorleyFbmSpec{s.perlin_period, s.perlin_octaves};
  if (field == "perlin_worley") return s.perlin_worley;
  for (size_t i = 0; i < s.worley.size(); ++i)
    if (field == fmt::format("worley[{}]", i)) return s.worley[i];
  return std::nullopt;
}
std::optional<WorleyFbmSpec> fbm_of(const NoiseDetailSpec& s, const std::string& field) {
  for (size_t i = 0; i < s.worley.size(); ++i)
    if (field == fmt::format("worley[{}]", i)) return s.worley[i];
  return std::nullopt;
}
std::optional<WorleyFbmSpec> fbm_of(const CurlSpec& s, const std::string& field) {
  if (field == "octaves") return WorleyFbmSpec{s.period, s.octaves};
  return std::nullopt;
}

// A default fBm whose finest octave is too fine for the size the preset
// wrote: the preset never named it, so say it is the default and what fits
// (the coarsest octaves kept, else one octave at the finest period the size
// allows).
std::string default_fbm_message(const std::string& field, const WorleyFbmSpec& f, int size) {
  const int limit = std::max(1, std::min(size / 2, 256));
  WorleyFbmSpec fit = f;
  while (fit.octaves > 1 && (long(fit.period) << (fit.octaves - 1)) > limit) --fit.octaves;
  if (fit.period > limit) fit = {limit, 1};
  const long finest = long(f.period) << (f.octaves - 1);
  const std::string value =
      field == "octaves" ? fmt::format("\"period\": {}, \"octaves\": {}", fit.period, fit.octaves)
                         : fmt::format("{{\"period\": {}, \"octaves\": {}}}", fit.period, fit.octaves);
  return fmt::format(
      "the default {} (period {}, octaves {}: finest period {}) does not fit size {}, whose "
      "finest period is at most {}: write {}{}{}, or a size of at least {}",
      field == "octaves" ? "fBm" : field, f.period, f.octaves, finest, size, limit,
      field == "octaves" ? "" : "it as ", value,
      field.rfind("worley[", 0) == 0 ? " (an entry of \"worley\" left {} keeps its default)" : "",
      2 * finest);
}

// The spec's problems as the preset's; one about an fBm that is the
// product's default (the schema fills defaults in, so a default is told by
// its value) says so and what to write instead.
template <typename Spec>
std::vector<ProductProblem> problems_of(const Spec& spec) {
  std::vector<ProductProblem> out;
  for (const SpecProblem& p : spec_problems(spec)) {
    const std::string pointer = p.field == "size" ? "/size" : pointer_from_field(p.field);
    const std::optional<WorleyFbmSpec> fbm = fbm_of(spec, p.field);
    const std::optional<WorleyFbmSpec> fallback = fbm_of(Spec{}, p.field);
    const bool is_default = fbm && fallback && fbm->period == fallback->period &&
                            fbm->octaves == fallback->octaves;
    out.push_back({pointer, is_default ? default_fbm_message(p.field, *fbm, spec.size) : p.message});
  }
  return out;
}

WorleyFbmSpec worley_from(const nlohmann::json& j, WorleyFbmSpec fallback) {
  if (!j.is_object()) return fallback;
  return {j.value("period", fallback.period), j.value("octaves", fallback.octaves)};
}

NoiseShapeSpec shape_spec(const OutputSpec& spec) {
  NoiseShapeSpec s;
  s.size = spec.size.at(0);
  s.seed = uint32_t(spec.options.value("seed", 0u));
  const nlohmann::json perlin = spec.options.value("perlin", nlohmann::json::object());
  s.perlin_period = perlin.value("period", s.perlin_period);
  s.perlin_octaves = perlin.value("octaves", s.perlin_octaves);
  s.perlin_gain = perlin.value("gain", s.perlin_gain);
  s.perlin_worley =
      worley_from(spec.options.value("perlin_worley", nlohmann::json()), s.perlin_worley);
  if (auto r = remap_from_name(option_string(spec, "remap", remap_name(s.remap)))) s.remap = *r;
  const nlohmann::json worley = spec.options.value("worley", nlohmann::json::array());
  for (size_t i = 0; i < s.worley.size() && i < worley.size(); ++i)
    s.worley[i] = worley_from(worley[i], s.worley[i]);
  return s;
}

NoiseDetailSpec detail_spec(const OutputSpec& spec) {
  NoiseDetailSpec s;
  s.size = spec.size.at(0);
  s.seed = uint32_t(spec.options.value("seed", 0u));
  const nlohmann::json worley = spec.options.value("worley", nlohmann::json::array());
  for (size_t i = 0; i < s.worley.size() && i < worley.size(); ++i)
    s.worley[i] = worley_from(worley[i], s.worley[i]);
  return s;
}

CurlSpec curl_spec(const OutputSpec& spec) {
  CurlSpec s;
  s.size = spec.size.at(0);
  s.seed = uint32_t(spec.options.value("seed", 0u));
  s.period = spec.options.value("period", s.period);
  s.octaves = spec.options.value("octaves", s.octaves);
  s.gain = spec.options.value("gain", s.gain);
  s.with_z = option_string(spec, "channels", "rgb") == "rgb";
  return s;
}

bool packed(const OutputSpec& spec) {
  return option_string(spec, "pack", "none") != "none";
}

Texture bake_shape(const Scene&, const OutputSpec& spec, const ProductInputs&,
                   const BakeContext& ctx) {
  Texture tex = bake_noise_shape(shape_spec(spec), ctx);
  // Not a conditional expression: its unpacked branch would copy the volume
  // (one serial pass over a fresh buffer); `return tex` moves it.
  if (packed(spec)) return pack_single_channel(tex, shape_pack_weights());
  return tex;
}

Texture bake_detail(const Scene&, const OutputSpec& spec, const ProductInputs&,
                    const BakeContext& ctx) {
  Texture tex = bake_noise_detail(detail_spec(spec), ctx);
  if (packed(spec)) return pack_single_channel(tex, detail_pack_weights());
  return tex;
}

Texture bake_curl_noise(const Scene&, const OutputSpec& spec, const ProductInputs&,
                        const BakeContext& ctx) {
  return bake_curl(curl_spec(spec), ctx);
}

template <typename Spec, Spec (*make)(const OutputSpec&)>
std::vector<ProductProblem> check(const OutputSpec& spec) {
  std::vector<ProductProblem> problems =
      equal_size_problems(spec, "the texture is a cube (square) and tiles on every axis");
  if (problems.empty()) problems = problems_of(make(spec));
  return problems;
}

ProductInfo noise_product(std::string name, std::string summary, std::vector<std::string> axes,
                          std::vector<int> size, std::vector<int> max_size, BakeFn bake,
                          double ns_per_texel, CheckFn check_fn) {
  ProductInfo p =
      basic_product(std::move(name), std::move(summary), std::move(axes), std::move(size),
                    std::move(max_size), std::move(bake), ns_per_texel);
  p.default_formats = {"dds", "png"};
  p.allowed_formats = {"dds", "exr", "ktx2", "vdb", "png"};
  p.default_dds_format = "unorm8";
  // Float noise has little redundancy: zip saves 1-4% for about 7x the
  // bake's CPU (docs/decisions/exr-compression.md).
  p.default_exr_compression = "none";
  p.default_vdb_compression = "none";  // Blosc: -14% for 2x the VDB write's CPU
  p.check = std::move(check_fn);
  p.default_mips = true;
  p.preview_tiled = true;
  p.preview_split = true;
  p.tileable = true;
  p.density_volume = p.axes.size() == 3;  // the volumes; curl is a 2D vector field
  p.sampling.wrap.assign(p.axes.size(), "repeat");
  return p;
}

}  // namespace

void add_noise_products(std::vector<ProductInfo>& r) {
  r.push_back(noise_product("noise_shape",
                            "tileable cloud shape volume: R Perlin-Worley, GBA Worley fBm "
                            "(Schneider 2015)",
                            {"x", "y", "z"}, {128, 128, 128}, {1024, 1024, 1024}, bake_shape, 50.0,
                            check<NoiseShapeSpec, shape_spec>));
  r.push_back(noise_product("noise_detail",
                            "tileable cloud detail volume: RGB Worley fBm at rising frequencies",
                            {"x", "y", "z"}, {32, 32, 32}, {1024, 1024, 1024}, bake_detail, 40.0,
                            check<NoiseDetailSpec, detail_spec>));
  r.push_back(noise_product(
      "curl", "tileable 2D curl noise (divergence free) to distort detail lookups", {"x", "y"},
      {128, 128}, {8192, 8192}, bake_curl_noise, 600.0, check<CurlSpec, curl_spec>));
}

}  // namespace skybake

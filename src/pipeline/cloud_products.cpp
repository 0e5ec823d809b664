// Cloud texture products (docs/clouds.md): the weather map, the cloud-type profiles
// and their height-gradient table, the high-altitude templates. What they
// contain comes from the scene's "clouds" section (schemas/clouds.schema.json,
// inline or a presets/clouds/ file, defaults filled in by the loader); the
// output objects only choose the encoding (schemas/products/weather,
// cloud_types, cirrus). The section is part of every one of their hashes
// (scene_sections), so editing it re-bakes them.
//
// clouds_section_problems() holds the rules of the section that a schema
// cannot say (ramp order, a coverage the rain floor allows, unique type
// names); its pointers are relative to the section.
#include "pipeline/cloud_products.hpp"

#include <fmt/format.h>

#include "clouds/cirrus.hpp"
#include "clouds/cloud_types.hpp"
#include "clouds/height_gradients.hpp"
#include "clouds/weather_map.hpp"
#include "core/error.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/product_options.hpp"
#include "pipeline/product_tables.hpp"

namespace skybake {

namespace {

using nlohmann::json;

const char* const kStandardTypes[4] = {"stratus", "stratocumulus", "cumulus", "cumulonimbus"};

json section(const json& clouds, const char* key) {
  return clouds.is_object() ? clouds.value(key, json::object()) : json::object();
}

uint32_t seed_of(const json& clouds) {
  return clouds.is_object() ? clouds.value("seed", 0u) : 0u;
}

std::vector<CloudTypeProfile> cloud_types_from(const json& clouds) {
  const json types = section(clouds, "cloud_types");
  std::vector<CloudTypeProfile> out = default_cloud_types();
  auto read = [](const json& j, CloudTypeProfile& t) {
    if (!j.is_object()) return;
    if (j.contains("density")) {
      const auto r = j["density"].get<std::vector<double>>();
      if (r.size() == 4) t.density = {r[0], r[1], r[2], r[3]};
    }
    if (j.contains("erosion")) {
      const auto e = j["erosion"].get<std::vector<double>>();
      if (e.size() == 2) t.erosion_base = e[0], t.erosion_top = e[1];
    }
  };
  for (CloudTypeProfile& t : out) read(types.value(t.name, json::object()), t);
  for (const json& extra : types.value("extra", json::array())) {
    CloudTypeProfile t;
    t.name = extra.value("name", std::string());
    t.erosion_base = t.erosion_top = 0.5;
    read(extra, t);
    out.push_back(t);
  }
  return out;
}

WeatherSpec weather_spec_from(const json& clouds) {
  const json w = section(clouds, "weather");
  WeatherSpec s;
  s.seed = seed_of(clouds);
  s.world_size_km = w.value("world_size_km", s.world_size_km);
  const json c = w.value("coverage", json::object());
  s.coverage.mean = c.value("mean", s.coverage.mean);
  s.coverage.feature_km = c.value("feature_km", s.coverage.feature_km);
  s.coverage.octaves = c.value("octaves", s.coverage.octaves);
  s.coverage.contrast = c.value("contrast", s.coverage.contrast);
  const json p = w.value("precipitation", json::object());
  s.precipitation.area = p.value("area", s.precipitation.area);
  s.precipitation.edge = p.value("edge", s.precipitation.edge);
  s.precipitation.feature_km = p.value("feature_km", s.precipitation.feature_km);
  s.precipitation.octaves = p.value("octaves", s.precipitation.octaves);
  s.precipitation.correlation = p.value("correlation", s.precipitation.correlation);
  const json t = w.value("type", json::object());
  s.type.mean = t.value("mean", s.type.mean);
  s.type.variation = t.value("variation", s.type.variation);
  s.type.feature_km = t.value("feature_km", s.type.feature_km);
  s.type.octaves = t.value("octaves", s.type.octaves);
  s.type_count = int(cloud_types_from(clouds).size());
  return s;
}

CirrusLayer layer_from(const json& j, CirrusLayer l) {
  if (!j.is_object()) return l;
  if (j.contains("period")) {
    const auto p = j["period"].get<std::vector<int>>();
    if (p.size() == 2) l.period = {p[0], p[1]};
  }
  l.octaves = j.value("octaves", l.octaves);
  l.coverage = j.value("coverage", l.coverage);
  return l;
}

CirrusSpec cirrus_spec_from(const json& clouds) {
  const json c = section(clouds, "cirrus");
  CirrusSpec s;
  s.seed = seed_of(clouds);
  s.streaks = layer_from(c.value("streaks", json::object()), s.streaks);
  s.cirrocumulus = layer_from(c.value("cirrocumulus", json::object()), s.cirrocumulus);
  s.altostratus = layer_from(c.value("altostratus", json::object()), s.altostratus);
  return s;
}

// "types[5].density" -> "/cloud_types/extra/1/density", "types[0].erosion"
// -> "/cloud_types/stratus/erosion".
std::string type_pointer(const std::string& field) {
  const size_t close = field.find(']');
  const size_t index = std::stoul(field.substr(6, close - 6));
  std::string tail = field.substr(close + 1);  // ".density[2]"
  if (!tail.empty() && tail[0] == '.') tail.erase(0, 1);
  const std::string rest = pointer_from_field(tail);
  const std::string base = index < 4 ? std::string("/cloud_types/") + kStandardTypes[index]
                                     : fmt::format("/cloud_types/extra/{}", index - 4);
  return base + (rest == "/" ? "" : rest);
}

}  // namespace

// Pointers relative to the section ("/weather/coverage/mean"). Not yet
// called by the loader (see checked_clouds).
std::vector<ProductProblem> clouds_section_problems(const nlohmann::json& clouds) {
  std::vector<ProductProblem> out;
  for (const SpecProblem& p : spec_problems(weather_spec_from(clouds)))
    if (p.field != "size" && p.field != "type_count")
      out.push_back({"/weather" + pointer_from_field(p.field), p.message});
  for (const SpecProblem& p : cloud_type_problems(cloud_types_from(clouds)))
    out.push_back({type_pointer(p.field), p.message});
  for (const SpecProblem& p : spec_problems(cirrus_spec_from(clouds)))
    if (p.field != "size") out.push_back({"/cirrus" + pointer_from_field(p.field), p.message});
  return out;
}

namespace {

// The scene's clouds section, checked. The loader's schema validation has
// run; the section rules are checked here too so that no baker ever sees a
// broken section (see clouds_section_problems for the load-time check).
const json& checked_clouds(const Scene& scene) {
  static const json empty = json::object();
  const json& clouds = scene.resolved.contains("clouds") ? scene.resolved["clouds"] : empty;
  const auto problems = clouds_section_problems(clouds);
  if (!problems.empty())
    throw PresetError(scene.file.string(), "/clouds" + problems[0].pointer, problems[0].rule);
  return clouds;
}

Texture bake_weather(const Scene& scene, const OutputSpec& out, const ProductInputs&,
                     const BakeContext& ctx) {
  WeatherSpec s = weather_spec_from(checked_clouds(scene));
  s.size = out.size.at(0);
  s.layout = option_string(out, "layout", "schneider") == "frostbite" ? WeatherLayout::frostbite
                                                                      : WeatherLayout::schneider;
  return bake_weather_map(s, ctx);
}

Texture bake_types(const Scene& scene, const OutputSpec& out, const ProductInputs&,
                   const BakeContext&) {
  CloudTypesSpec s;
  s.types = cloud_types_from(checked_clouds(scene));
  s.height = out.size.at(0);
  s.type_width = option_int(out, "type_width", s.type_width);
  return bake_cloud_types(s);
}

Texture bake_gradients(const Scene& scene, const OutputSpec& out, const ProductInputs&,
                       const BakeContext&) {
  const std::vector<CloudTypeProfile> types = cloud_types_from(checked_clouds(scene));
  HeightGradientsSpec s;
  s.height = out.size.at(0);
  for (int i = 0; i < 4; ++i) s.ramps[i] = types[i].density;
  return bake_height_gradients(s);
}

Texture bake_high_clouds(const Scene& scene, const OutputSpec& out, const ProductInputs&,
                         const BakeContext& ctx) {
  CirrusSpec s = cirrus_spec_from(checked_clouds(scene));
  s.width = out.size.at(0);
  s.height = out.size.at(1);
  return bake_cirrus(s, ctx);
}

std::vector<ProductProblem> square_problems(const OutputSpec& spec) {
  return equal_size_problems(spec, "the weather map is square (world_size_km on both axes)");
}

ProductInfo cloud_product(std::string name, std::string summary, std::vector<std::string> axes,
                          std::vector<int> size, std::vector<int> max_size, BakeFn bake,
                          double ns_per_texel, bool tileable) {
  ProductInfo p =
      basic_product(std::move(name), std::move(summary), std::move(axes), std::move(size),
                    std::move(max_size), std::move(bake), ns_per_texel);
  p.default_formats = {"dds", "exr", "png"};
  p.allowed_formats = {"dds", "exr", "ktx2", "png"};
  p.scene_sections = {"clouds"};
  p.default_dds_format = "unorm8";
  p.default_mips = tileable;
  p.preview_tiled = tileable;
  p.preview_split = true;
  p.sampling.wrap.assign(2, tileable ? "repeat" : "clamp");
  return p;
}

}  // namespace

void add_cloud_products(std::vector<ProductInfo>& r) {
  ProductInfo weather = cloud_product(
      "weather",
      "tileable weather map: R coverage, G precipitation, B cloud type (Schneider 2016); "
      "layout frostbite: R density, G type",
      {"x", "y"}, {512, 512}, {8192, 8192}, bake_weather, 1000.0, true);
  weather.check = square_problems;
  r.push_back(std::move(weather));
  r.push_back(cloud_product("cloud_types",
                            "cloud-type texture: x type, y height; R density, G erosion "
                            "(Frostbite 2016 5.3.1)",
                            {"height"}, {128}, {4096}, bake_types, 100.0, false));
  r.push_back(cloud_product("height_gradients",
                            "density-height gradients of stratus, stratocumulus, cumulus, "
                            "cumulonimbus as RGBA columns (Schneider 2016 4.3.2)",
                            {"height"}, {128}, {4096}, bake_gradients, 100.0, false));
  r.push_back(cloud_product("cirrus",
                            "tileable high-altitude templates: R cirrus streaks, G cirrocumulus, "
                            "B altostratus",
                            {"x", "y"}, {512, 512}, {8192, 8192}, bake_high_clouds, 900.0, true));
}

}  // namespace skybake

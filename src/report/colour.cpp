#include "report/colour.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "atmosphere/skyview_lut.hpp"
#include "core/colour.hpp"
#include "core/math.hpp"
#include "io/atomic_file.hpp"
#include "io/png_preview.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/spectral_bake.hpp"
#include "reference/spectral_path_tracer.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {

ColourSetup ColourSetup::full() {
  ColourSetup s;
  s.colour_skyview_size = {192, 108};
  s.colour_wavelengths = {15, 42};
  s.colour_reference_wavelengths = 42;
  s.colour_samples = 16384;
  s.colour_sun_elevations_deg = {60.0, 10.0, 2.0, 0.0, -3.0, -6.0};
  s.colour_altitudes_m = {1.0, 10000.0};
  return s;
}

ColourSetup ColourSetup::quick() {
  ColourSetup s = full();
  s.colour_skyview_size = {64, 36};
  s.colour_samples = 64;
  return s;
}

namespace {

// One table of the comparison: a name and its wavelength count (0: RGB).
// The table at the reference's count samples the spectrum uniformly, as
// the reference does; the others as the scene asks.
struct ColourTable {
  std::string name;
  int wavelengths = 0;
  Texture skyview;
  bool uniform = false;
};

// The scene's tables with a sky-view layer per view, for `table`
// (0 wavelengths: the RGB coefficients with the sun's colour as the sun).
Scene colour_scene(const Scene& base, const ColourSetup& s, const ColourTable& table) {
  Scene sc = base;
  OutputSpec sky = operating_spec(base, "skyview");
  sky.size = s.colour_skyview_size;
  sky.options["views"] = json::array();
  for (double alt : s.colour_altitudes_m)
    for (double e : s.colour_sun_elevations_deg)
      sky.options["views"].push_back({{"altitude_km", alt * 1e-3}, {"sun_zenith_deg", 90.0 - e}});
  sc.outputs = {operating_spec(base, "transmittance"), operating_spec(base, "multiscattering"), sky};
  if (table.wavelengths == 0) {
    sc.spectral = nullptr;
  } else {
    auto sp = std::make_shared<SpectralScene>(*base.spectral);
    sp->wavelengths = table.wavelengths;
    if (table.uniform) sp->sampling = SpectralSampling::uniform;
    sc.spectral = sp;
  }
  return sc;
}

Texture colour_skyview(const Scene& sc) {
  const ProductGraph g = build_product_graph(sc, {});
  const size_t n = g.nodes.size();
  std::vector<std::optional<Texture>> t(n);
  if (sc.spectral) {
    t = bake_spectral_graph(sc, g, std::vector<char>(n, 1), std::vector<char>(n, 0), {}).textures;
  } else {
    for (size_t i = 0; i < n; ++i) {
      ProductInputs in;
      for (size_t d : g.nodes[i].deps) in[g.nodes[d].info->name] = &*t[d];
      t[i] = g.nodes[i].info->bake(sc, g.nodes[i].spec, in, {});
    }
  }
  for (size_t i = 0; i < n; ++i)
    if (g.nodes[i].info->name == "skyview") return std::move(*t[i]);
  return {};
}

// The compared texels of a layer: zenith, mid elevation and just above the
// horizon, toward the sun, across it and away from it.
std::vector<glm::ivec2> colour_texels(int width, int height) {
  std::vector<glm::ivec2> texels;
  for (int y : {0, height / 4, height / 2 - 2})
    for (int x : {0, width / 4, width / 2}) texels.push_back({x, std::max(y, 0)});
  return texels;
}

double colour_delta_uv(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec2 d = uv_prime_from_xyz(a) - uv_prime_from_xyz(b);
  return std::hypot(d.x, d.y);
}

// The reference's 95% interval in Delta u'v': its components' intervals
// through the first-order change of u'v'.
double colour_reference_uv_ci(const glm::dvec3& xyz, const glm::dvec3& ci) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 p = xyz;
    p[i] += ci[i];
    sum += std::pow(colour_delta_uv(p, xyz), 2);
  }
  return std::sqrt(sum);
}

}  // namespace

namespace {

struct ColourFrame {
  glm::dmat3 to_xyz;  // the tables' RGB to XYZ
  double sun_y = 1.0;  // the sun's luminance in the tables' units
  SpectralGrid reference;
  int reference_table = -1;  // the table baked at the reference count, or -1
};

glm::dvec3 colour_table_xyz(const ColourTable& t, const ColourFrame& f, int x, int y, int layer) {
  const float* v = t.skyview.texel(x, y, 0, layer);
  return f.to_xyz * glm::dvec3(v[0], v[1], v[2]) / f.sun_y;
}

// One view: the largest errors of each table over the view's directions.
json colour_view(const ReportInputs& in, const ColourSetup& s, const std::vector<ColourTable>& tables,
                 const ColourFrame& f, int layer, double altitude_m, double elevation_deg) {
  const Atmosphere& atm = in.scene.atmosphere;
  const double r = atm.bottom_radius_m + altitude_m;
  const double e = elevation_deg * kDeg;
  const glm::dvec3 sun(std::cos(e), 0.0, std::sin(e));
  SkyviewLutSpec spec;
  spec.width = s.colour_skyview_size.at(0);
  spec.height = s.colour_skyview_size.at(1);
  PathTracerSpec pt;
  pt.samples = s.colour_samples;
  json out = {{"altitude_m", altitude_m}, {"sun_elevation_deg", elevation_deg}};
  double ref_uv_ci = 0.0, ref_y_ci = 0.0;
  // Per table: Delta u'v', |dY / Y|, and both against the reference count's table.
  std::vector<glm::dvec4> worst(tables.size(), glm::dvec4(0.0));
  for (const glm::ivec2& t : colour_texels(spec.width, spec.height)) {
    const glm::dvec2 uv = skyview_texel_uv(atm, r, spec, t.x, t.y);
    const glm::dvec3 dir = skyview_vector_from_direction(view_from_skyview_uv(atm, r, uv, spec.width, spec.height));
    const SpectralRadianceEstimate ref = trace_spectral_sky(
        atm, in.scene.spectral->medium, f.reference, glm::dvec3(0.0, 0.0, r), dir, sun, pt);
    ref_uv_ci = std::max(ref_uv_ci, colour_reference_uv_ci(ref.xyz, ref.ci95));
    ref_y_ci = std::max(ref_y_ci, ref.ci95.y / ref.xyz.y);
    for (size_t k = 0; k < tables.size(); ++k) {
      const glm::dvec3 xyz = colour_table_xyz(tables[k], f, t.x, t.y, layer);
      worst[k].x = std::max(worst[k].x, colour_delta_uv(xyz, ref.xyz));
      worst[k].y = std::max(worst[k].y, std::abs(xyz.y / ref.xyz.y - 1.0));
      if (f.reference_table >= 0) {
        const glm::dvec3 own = colour_table_xyz(tables[size_t(f.reference_table)], f, t.x, t.y, layer);
        worst[k].z = std::max(worst[k].z, colour_delta_uv(xyz, own));
        worst[k].w = std::max(worst[k].w, std::abs(xyz.y / own.y - 1.0));
      }
    }
  }
  for (size_t k = 0; k < tables.size(); ++k)
    out[tables[k].name] = {{"delta_uv", worst[k].x},
                           {"luminance_error", worst[k].y},
                           {"table_delta_uv", worst[k].z},
                           {"table_luminance_error", worst[k].w}};
  out["ref_delta_uv_ci95"] = ref_uv_ci;
  out["ref_luminance_ci95"] = ref_y_ci;
  return out;
}

// Side by side per view (rows) the tables (columns), each view's panels
// scaled by one factor so that the reference-count table's mean luminance
// over the sky is 0.5 before Reinhard's curve.
std::string colour_previews(const ReportInputs& in, const std::vector<ColourTable>& tables,
                            const ColourFrame& f, const std::vector<std::string>& view_names) {
  const Texture& first = tables.front().skyview;
  const int w = first.width, h = first.height, views = first.layers, nt = int(tables.size());
  Texture picture(w, h, 1, views * nt, {"R", "G", "B"});
  PreviewOptions options;
  options.tonemap = Tonemap::reinhard;
  options.exposure = 1.0;
  options.max_columns = nt;
  const ColourTable& key = tables[size_t(f.reference_table >= 0 ? f.reference_table : nt - 1)];
  for (int v = 0; v < views; ++v) {
    double mean = 0.0;
    for (int y = 0; y < h / 2; ++y)
      for (int x = 0; x < w; ++x) mean += colour_table_xyz(key, f, x, y, v).y;
    const double scale = 0.5 / std::max(mean / (w * (h / 2)), 1e-30) / f.sun_y;
    for (int k = 0; k < nt; ++k) {
      options.panel_labels.push_back(tables[size_t(k)].name + " " + view_names.at(size_t(v)));
      const float* src = tables[size_t(k)].skyview.texel(0, 0, 0, v);
      float* dst = picture.texel(0, 0, 0, v * nt + k);
      for (size_t i = 0; i < size_t(w) * h * 3; ++i) dst[i] = float(std::max(0.0, src[i] * scale));
    }
  }
  create_folder(in.folder);
  const std::string name = "colour_previews.png";
  AtomicFile file(in.folder / name);
  file.write([&](const fs::path& temp) { write_png_preview(temp.string(), picture, options); });
  file.commit();
  return name;
}

}  // namespace

json colour_report(const ReportInputs& in, const ColourSetup& s) {
  if (!in.scene.spectral) return {{"skipped", "the scene asks for no spectral bake (\"spectral\")"}};
  std::vector<ColourTable> tables = {{"rgb3", 0, {}}};
  ColourFrame f;
  f.reference = spectral_grid(s.colour_reference_wavelengths, SpectralSampling::uniform);
  for (int n : s.colour_wavelengths) {
    const int count = spectral_grid(n).wavelength_count();
    tables.push_back({fmt::format("n{}", count), n, {}, count == f.reference.wavelength_count()});
  }
  f.to_xyz = xyz_from_rgb(chromaticities_of(in.scene.spectral->colour_space));
  f.sun_y = (f.to_xyz * in.scene.atmosphere.sun_illuminance).y;
  for (size_t k = 0; k < tables.size(); ++k) {
    in.stage("colour: sky-view at " + tables[k].name);
    tables[k].skyview = colour_skyview(colour_scene(in.scene, s, tables[k]));
    if (tables[k].uniform) f.reference_table = int(k);
  }
  json out = {{"reference_wavelengths", f.reference.wavelength_count()},
              {"samples", s.colour_samples},
              {"colour_space", colour_space_name(in.scene.spectral->colour_space)},
              {"views", json::array()}};
  int layer = 0;
  std::vector<std::string> view_names;
  for (double alt : s.colour_altitudes_m)
    for (double e : s.colour_sun_elevations_deg) {
      view_names.push_back(fmt::format("{}m sun {}", alt, e));
      in.stage(fmt::format("colour: reference at {} m, sun {} deg", alt, e));
      out["views"].push_back(colour_view(in, s, tables, f, layer++, alt, e));
    }
  for (const ColourTable& t : tables) {
    double duv = 0.0, dy = 0.0;
    for (const json& v : out["views"]) {
      duv = std::max(duv, v[t.name]["delta_uv"].get<double>());
      dy = std::max(dy, v[t.name]["luminance_error"].get<double>());
    }
    out["worst"][t.name] = {{"delta_uv", duv}, {"luminance_error", dy}};
  }
  out["preview"] = colour_previews(in, tables, f, view_names);
  return out;
}

}  // namespace skybake

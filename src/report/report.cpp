#include "report/report.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "atmosphere/sky_preview.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/png_preview.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/product_options.hpp"
#include "report/bruneton.hpp"
#include "report/html.hpp"
#include "report/ladders.hpp"
#include "report/precision.hpp"
#include "report/sky_radiance.hpp"
#include "core/suggest.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

using ProductSection = nlohmann::json (*)(const ReportInputs&);

// The tables measured by a ladder, in dependency order.
const std::vector<std::pair<std::string, ProductSection>>& measured_products() {
  static const std::vector<std::pair<std::string, ProductSection>> table = {
      {"transmittance", transmittance_report},
      {"multiscattering", multiscattering_report},
      {"skyview", skyview_report},
      {"aerial_perspective", aerial_perspective_report},
      {"scattering", scattering_report},
      {"single_mie", single_mie_report},
      {"irradiance", irradiance_report},
      {"scattering3d", scattering3d_report},
      {"gathering_sum", gathering_sum_report}};
  return table;
}

bool is_measured(const std::string& product) {
  for (const auto& [name, fn] : measured_products())
    if (name == product) return true;
  return false;
}

// The products of the report: those the scene requests, restricted to `only`.
std::vector<std::string> selected_products(const Scene& scene,
                                           const std::vector<std::string>& only) {
  std::vector<std::string> asked;
  for (const OutputSpec& o : scene.outputs) asked.push_back(o.product);
  for (const std::string& name : only) {
    if (!find_product(name))
      throw UsageError(fmt::format("--products: unknown product '{}'{}", name,
                                   did_you_mean(name, product_names())));
    if (std::find(asked.begin(), asked.end(), name) == asked.end())
      throw UsageError(
          fmt::format("--products: scene '{}' ({}) does not request '{}'; it requests: {}",
                      scene.name, scene.file.string(), name, fmt::join(asked, ", ")));
  }
  if (only.empty()) return asked;
  std::vector<std::string> out;
  for (const std::string& p : asked)
    if (std::find(only.begin(), only.end(), p) != only.end()) out.push_back(p);
  return out;
}

// What the report says of a product it does not measure with a ladder.
nlohmann::json unmeasured_product(const std::string& product) {
  const ProductInfo* info = find_product(product);
  const bool atmosphere =
      info && std::find(info->scene_sections.begin(), info->scene_sections.end(), "atmosphere") !=
                  info->scene_sections.end();
  if (product == "sky_preview")
    return {{"product", product},
            {"kind", "preview"},
            {"note",
             "pictures rendered from the tables (sky_preview.png in this folder); how close "
             "the rendered sky is to the truth is the sky radiance section"}};
  if (atmosphere)
    return {{"product", product},
            {"kind", "not_measured"},
            {"note", "no ladder for this product in this version of the report"}};
  return {{"product", product},
          {"kind", "exact"},
          {"note",
           "an exact evaluation of its function at every texel (noise, clouds): no "
           "discretisation to measure; check-tiling checks its seams"}};
}

Texture bake_preview(const Scene& scene, const ReportLevel& level, const Texture& transmittance,
                     const Texture& multiscattering) {
  SkyPreviewSpec spec;
  spec.width = level.preview_width;
  spec.height = level.preview_height;
  if (const OutputSpec* o = scene.find_output("sky_preview"))
    spec.camera_altitude_m =
        option_double(*o, "camera_altitude_km", spec.camera_altitude_m * 1e-3) * 1e3;
  return bake_sky_preview(scene.atmosphere, transmittance, multiscattering, spec, BakeContext{});
}

void write_png_atomic(const fs::path& path, const Texture& tex) {
  AtomicFile file(path);
  PreviewOptions opt;
  opt.exposure = 1.0;  // the preview is display-referred already
  write_png_preview(file.temp_path().string(), tex, opt);
  file.commit();
}

// A section's JSON with the wall seconds it took ("section_seconds").
nlohmann::json timed(nlohmann::json (*section)(const ReportInputs&), const ReportInputs& in) {
  const auto t0 = std::chrono::steady_clock::now();
  nlohmann::json j = section(in);
  j["section_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

fs::path create_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  return folder;
}

// Every section that needs the atmosphere's tables: the operating-point
// tables are baked once and shared; the preview goes into `folder`.
void add_atmosphere_sections(const Scene& scene, const ReportLevel& level,
                             const std::vector<std::string>& products, const ReportStage& on_stage,
                             const fs::path& folder, nlohmann::json& report) {
  const Atmosphere& atm = scene.atmosphere;
  const auto wants = [&](const char* p) {
    return std::find(products.begin(), products.end(), p) != products.end();
  };
  if (on_stage) on_stage("baking the operating-point tables");
  const Texture transmittance = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  const Texture multiscattering = bake_multiscattering_lut(
      atm, transmittance, multiscattering_spec(operating_spec(scene, "multiscattering")),
      BakeContext{});
  TransmittanceLutSpec fine;
  fine.width = level.reference_transmittance_size[0];
  fine.height = level.reference_transmittance_size[1];
  fine.steps = level.reference_transmittance_steps;
  const Texture reference_transmittance = bake_transmittance_lut(atm, fine, BakeContext{});
  const ReportInputs in{scene,   level, transmittance, multiscattering, reference_transmittance,
                        on_stage};

  for (const auto& [name, section] : measured_products()) {
    if (!wants(name.c_str())) continue;
    nlohmann::json p = timed(section, in);
    report["precision"]["half"].push_back({{"product", name},
                                           {"float", p["half"]["float"]},
                                           {"half", p["half"]["half"]},
                                           {"storage", p["half"]["storage"]}});
    report["products"].push_back(std::move(p));
  }
  // The sky as an engine renders it from either family of tables.
  if (wants("skyview") || wants("scattering"))
    report["sky_radiance"] = timed(sky_radiance_report, in);
  if (wants("transmittance"))
    report["precision"]["horizon_transmittance"] = timed(horizon_transmittance_report, in);
  const auto t_bruneton = std::chrono::steady_clock::now();
  report["bruneton_comparison"] = bruneton_comparison_report(in, report["sky_radiance"]);
  report["bruneton_comparison"]["section_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_bruneton).count();

  if (on_stage) on_stage("sky preview");
  write_png_atomic(create_folder(folder) / "sky_preview.png",
                   bake_preview(scene, level, transmittance, multiscattering));
  report["files"]["preview"] = "sky_preview.png";
}

}  // namespace

ReportResult run_report(const Scene& scene, const ReportOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::string> products = selected_products(scene, options.products);
  ReportLevel level = options.quick ? ReportLevel::quick() : ReportLevel::full();
  if (options.path_samples > 0) level.path_samples = options.path_samples;
  ReportResult result;
  result.folder = options.out_dir / scene.name / "report";

  nlohmann::json report = {
      {"tool", "skybake " SKYBAKE_VERSION},
      {"scene", scene.name},
      {"preset", scene.file.string()},
      {"level", level.name},
      {"level_settings", level_json(level)},
      {"products", nlohmann::json::array()},
      {"sky_radiance", nullptr},
      {"precision", {{"horizon_transmittance", nullptr}, {"half", nlohmann::json::array()}}},
      {"bruneton_comparison", nullptr},
      {"files", {{"json", "report.json"}, {"html", "report.html"}}}};
  const bool needs_tables =
      std::any_of(products.begin(), products.end(), is_measured) ||
      std::find(products.begin(), products.end(), "scattering") != products.end();
  if (scene.has_atmosphere && needs_tables)
    add_atmosphere_sections(scene, level, products, options.on_stage, result.folder, report);
  for (const std::string& p : products)
    if (!is_measured(p)) report["products"].push_back(unmeasured_product(p));

  report["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  create_folder(result.folder);
  write_text_atomic(result.folder / "report.json", report.dump(2) + "\n");
  write_text_atomic(result.folder / "report.html", report_html(report));
  result.report = std::move(report);
  return result;
}

namespace {

// Worst-channel relative RMSE of both models against the path tracer.
nlohmann::json bruneton_summary(const nlohmann::json& b) {
  if (b.is_null()) return nullptr;
  if (b["status"] != "measured") return {{"status", b["status"]}};
  return {
      {"status", "measured"},
      {"orders_used", b["bruneton"]["orders_used"]},
      {"hillaire_rel_rmse", b["hillaire"]["worst"]["rel_rmse"]},
      {"bruneton_rel_rmse", b["bruneton_vs_path_tracer"]["worst"]["rel_rmse"]},
      {"bruneton_exact_mie_rel_rmse", b["bruneton_exact_mie_vs_path_tracer"]["worst"]["rel_rmse"]},
      {"target", b["target"]["status"]},
      {"exact_mie_target", b["exact_mie_target"]["status"]},
      {"hybrid_target", b["hybrid_target"]["status"]}};
}

}  // namespace

nlohmann::json report_summary(const ReportResult& result) {
  const nlohmann::json& r = result.report;
  nlohmann::json products = nlohmann::json::array();
  for (const auto& p : r["products"]) {
    if (p["kind"] != "lut") {
      products.push_back({{"product", p["product"]}, {"kind", p["kind"]}});
      continue;
    }
    const auto& op = p["ladder"][p["operating_point"].get<size_t>()];
    products.push_back({{"product", p["product"]},
                        {"kind", "lut"},
                        {"points", p["ladder"].size()},
                        {"operating_point", op["settings"]},
                        {"seconds", op["seconds"]},
                        {"max_rel", op["max_rel"]},
                        {"rms_rel", op["rms_rel"]},
                        {"on_pareto_front", op["pareto"]},
                        {"half_max_rel", p["half"]["half"]["max_rel"]}});
  }
  nlohmann::json sky = nullptr;
  if (!r["sky_radiance"].is_null()) {
    const auto& s = r["sky_radiance"];
    sky = {{"paths", s["path_tracer"]["samples"]},
           {"multiple_rel_rmse", s["multiple"]["worst"]["rel_rmse"]},
           {"multiple_rel_rmse_denoised", s["multiple"]["worst"]["rel_rmse_denoised"]},
           {"noise_rel_rms", s["multiple"]["worst"]["noise_rel_rms"]},
           {"single_vs_quadrature_rel_rmse", s["single_vs_quadrature"]["worst"]["rel_rmse"]},
           {"target", s["target"]["status"]}};
  }
  return {{"scene", r["scene"]},
          {"level", r["level"]},
          {"folder", result.folder.string()},
          {"html", (result.folder / "report.html").string()},
          {"json", (result.folder / "report.json").string()},
          {"seconds", r["seconds"]},
          {"products", products},
          {"sky_radiance", sky},
          {"bruneton_comparison", bruneton_summary(r["bruneton_comparison"])}};
}

}  // namespace skybake

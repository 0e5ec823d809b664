#include "report/report.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product.hpp"
#include "report/html.hpp"
#include "report/sections.hpp"
#include "core/suggest.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

// The products of the report: those the scene requests, restricted to `only`.
std::vector<std::string> selected_products(const Scene& scene,
                                           const std::vector<std::string>& only) {
  std::vector<std::string> asked;
  for (const OutputSpec& o : scene.outputs) asked.push_back(o.product);
  for (const std::string& name : only) {
    if (!find_product(name))
      throw UsageError(fmt::format("--only: unknown product '{}'{}", name,
                                   did_you_mean(name, product_names())));
    if (std::find(asked.begin(), asked.end(), name) == asked.end())
      throw UsageError(
          fmt::format("--only: scene '{}' ({}) does not request '{}'; it requests: {}",
                      scene.name, scene.file.string(), name, fmt::join(asked, ", ")));
  }
  if (only.empty()) return asked;
  std::vector<std::string> out;
  for (const std::string& p : asked)
    if (std::find(only.begin(), only.end(), p) != only.end()) out.push_back(p);
  return out;
}

// What the report says of a product it does not measure with a ladder:
// its kind and a note.
struct Unmeasured {
  const char* kind;
  const char* note;
};

Unmeasured unmeasured_kind(const std::string& product) {
  if (product == "sky_preview")
    return {"preview",
            "pictures rendered from the tables (sky_preview.png in this folder); how close the "
            "rendered sky is to the truth is the sky radiance section"};
  if (product == "sky_irradiance")
    return {"section",
            "measured against the path tracer in the sky_irradiance section: the decode, L2's "
            "own limit and the read between texels"};
  if (product == "sky_environment")
    return {"not_measured",
            "no ladder; the test suite checks level 0 against the integrated radiance and each "
            "GGX level against a brute-force convolution (docs/runtime.md, \"Sky environment\")"};
  const ProductInfo* info = find_product(product);
  if (info && std::find(info->scene_sections.begin(), info->scene_sections.end(),
                        "atmosphere") != info->scene_sections.end())
    return {"not_measured", "no ladder for this product in this version of the report"};
  return {"exact",
          "an exact evaluation of its function at every texel (noise, clouds): no "
          "discretisation to measure; check-tiling checks its seams"};
}

nlohmann::json unmeasured_product(const std::string& product) {
  const Unmeasured u = unmeasured_kind(product);
  return {{"product", product}, {"kind", u.kind}, {"note", u.note}};
}

// A section's JSON with the wall seconds it took ("section_seconds").
nlohmann::json timed(const ReportSection& section, const ReportInputs& in,
                     const nlohmann::json& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  nlohmann::json j = section.run(in, settings);
  if (j.is_object())
    j["section_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

// Puts a section's JSON at its place; a product's half round trip is also
// listed with the others under "precision".
void place(const ReportSection& section, nlohmann::json j, nlohmann::json& report) {
  if (j.is_object() && j.contains("half")) {
    const nlohmann::json& half = j["half"];
    report["precision"]["half"].push_back({{"product", j.at("product")},
                                           {"float", half["float"]},
                                           {"half", half["half"]},
                                           {"storage", half["storage"]}});
  }
  report[nlohmann::json::json_pointer(section.place)] = std::move(j);
}

// The tables every section reads, baked once at the preset's settings (the
// operating point), and the fine transmittance table of the fine references.
struct OperatingTables {
  Texture transmittance, multiscattering, reference_transmittance;
};

OperatingTables bake_operating_tables(const Scene& scene, const ReportLevel& level) {
  const Atmosphere& atm = scene.atmosphere;
  OperatingTables t;
  t.transmittance = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  t.multiscattering = bake_multiscattering_lut(
      atm, t.transmittance, multiscattering_spec(operating_spec(scene, "multiscattering")),
      BakeContext{});
  TransmittanceLutSpec fine;
  fine.width = level.reference_transmittance_size.at(0);
  fine.height = level.reference_transmittance_size.at(1);
  fine.steps = level.reference_transmittance_steps;
  t.reference_transmittance = bake_transmittance_lut(atm, fine, BakeContext{});
  return t;
}

// Every section of the table that covers one of `products`, in order.
void run_sections(const Scene& scene, const nlohmann::json& settings,
                  const std::vector<std::string>& products, const ReportStage& on_stage,
                  const fs::path& folder, nlohmann::json& report) {
  const ReportLevel level = settings.get<ReportLevel>();
  if (on_stage) on_stage("baking the operating-point tables");
  const OperatingTables t = bake_operating_tables(scene, level);
  const ReportInputs in{
      scene,  level,  t.transmittance, t.multiscattering, t.reference_transmittance,
      report, folder, on_stage};
  for (const ReportSection& section : report_sections())
    if (section_runs(section, products)) place(section, timed(section, in, settings), report);
}

}  // namespace

ReportResult run_report(const Scene& scene, const ReportOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::string> products = selected_products(scene, options.products);
  nlohmann::json settings = level_settings(options.quick);
  if (options.path_samples > 0) settings["path_samples"] = options.path_samples;  // sky radiance's
  ReportResult result;
  result.folder = options.out_dir / scene.name / "report";

  nlohmann::json report = {
      {"tool", "skybake " SKYBAKE_VERSION},
      {"scene", scene.name},
      {"preset", scene.file.string()},
      {"level", settings["name"]},
      {"level_settings", settings},
      {"products", nlohmann::json::array()},
      {"sky_radiance", nullptr},
      {"hillaire_runtime", nullptr},
      {"precision", {{"horizon_transmittance", nullptr}, {"half", nlohmann::json::array()}}},
      {"bruneton_comparison", nullptr},
      {"files", {{"json", "report.json"}, {"html", "report.html"}}}};
  // Every section reads the atmosphere's tables.
  const bool any_section =
      std::any_of(report_sections().begin(), report_sections().end(),
                  [&](const ReportSection& s) { return section_runs(s, products); });
  if (scene.has_atmosphere && any_section)
    run_sections(scene, settings, products, options.on_stage, result.folder, report);
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

// skybake report end to end (docs/report.md): one quick Earth report (a few
// seconds), checked through report.json, the --json summary, report.html and
// the preview; plus the usage error, a noise-only scene and the sky light preset. The Bruneton
// family's ladders are in report_ladders_accuracy_test.cpp. ctest runs every
// TEST in its own process, so the checks of the one report are functions
// called from a single TEST rather than TESTs sharing a static (which would
// run the report once per case).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

struct QuickEarth {
  test::RunResult run;
  fs::path folder;
  json report;
};

const QuickEarth& quick_earth() {
  static const QuickEarth result = [] {
    QuickEarth r;
    const fs::path out = test::fresh_dir("report_earth");
    r.run = test::run_skybake({"report", test::source_path("presets/earth.json").string(),
                               "--quick", "-o", out.string(), "--json", "-q"});
    r.folder = out / "earth" / "report";
    if (fs::exists(r.folder / "report.json"))
      r.report = json::parse(test::read_file(r.folder / "report.json"));
    return r;
  }();
  return result;
}

const json& product(const std::string& name) {
  for (const json& p : quick_earth().report["products"])
    if (p["product"] == name) return p;
  static const json none;
  ADD_FAILURE() << "no product " << name << " in report.json";
  return none;
}

// A ladder axis's value as a number to sort by (sizes by texel count).
double axis_value(const json& v) {
  if (!v.is_array()) return v.get<double>();
  double n = 1;
  for (const json& x : v) n *= x.get<double>();
  return n;
}

// The ladder points that differ from the operating point only in `axis`,
// sorted by the axis; their rms_rel.
std::vector<double> errors_along(const json& p, const std::string& axis) {
  const json& op = p["ladder"][p["operating_point"].get<size_t>()]["settings"];
  std::vector<std::pair<double, double>> points;
  for (const json& q : p["ladder"]) {
    json others = q["settings"], op_others = op;
    others.erase(axis);
    op_others.erase(axis);
    if (others == op_others)
      points.push_back({axis_value(q["settings"][axis]), q["rms_rel"].get<double>()});
  }
  std::sort(points.begin(), points.end());
  std::vector<double> errors;
  for (const auto& [x, e] : points) errors.push_back(e);
  return errors;
}

void check_files() {
  SCOPED_TRACE("check_files");
  const QuickEarth& r = quick_earth();
  EXPECT_EQ(r.run.exit_code, 0) << r.run.err;
  EXPECT_TRUE(fs::exists(r.folder / "report.json"));
  EXPECT_TRUE(fs::exists(r.folder / "report.html"));
  EXPECT_TRUE(fs::exists(r.folder / "sky_preview.png"));
  EXPECT_EQ(r.report["scene"], "earth");
  EXPECT_EQ(r.report["level"], "quick");
  // The report does not bake the scene: no manifest, no outputs beside it.
  EXPECT_EQ(test::list_files(r.folder.parent_path()),
            (std::vector<std::string>{"report/report.html", "report/report.json",
                                      "report/sky_preview.png"}));
}

void check_ladders() {
  SCOPED_TRACE("check_ladders");
  for (const char* name : {"transmittance", "multiscattering", "skyview", "aerial_perspective"}) {
    const json& p = product(name);
    ASSERT_EQ(p["kind"], "lut") << name;
    ASSERT_GE(p["ladder"].size(), 4u) << name;
    int operating = 0, front = 0;
    for (const json& q : p["ladder"]) {
      EXPECT_GT(q["seconds"].get<double>(), 0.0) << name << " " << q["label"];
      EXPECT_TRUE(std::isfinite(q["max_rel"].get<double>())) << name << " " << q["label"];
      EXPECT_LE(q["rms_rel"].get<double>(), q["max_rel"].get<double>()) << name;
      operating += q["operating_point"].get<bool>();
      front += q["pareto"].get<bool>();
    }
    EXPECT_EQ(operating, 1) << name;
    EXPECT_GE(front, 1) << name;
    EXPECT_TRUE(p["ladder"][p["operating_point"].get<size_t>()]["operating_point"].get<bool>());
  }
}

void check_error_falls() {
  SCOPED_TRACE("check_error_falls");
  // Non-strictly (5% slack for the plateau where another axis dominates),
  // and strictly from the first to the last point.
  for (const char* name : {"transmittance", "multiscattering", "skyview", "aerial_perspective"}) {
    const json& p = product(name);
    bool falls = false;
    for (const auto& [axis, values] : p["axes"].items()) {
      const std::vector<double> e = errors_along(p, axis);
      if (e.size() < 2) continue;
      bool monotone = e.back() < e.front();
      for (size_t i = 1; i < e.size(); ++i) monotone = monotone && e[i] <= 1.05 * e[i - 1];
      falls = falls || monotone;
    }
    EXPECT_TRUE(falls) << name << ": no axis along which the error falls";
  }
}

void check_transmittance_accuracy() {
  SCOPED_TRACE("check_transmittance_accuracy");
  // 256x64, 6 steps (8-point rule) against adaptive quadrature: measured rms 1.3e-3 and
  // max 2.2e-2 (grazing rays high up, where T changes by orders of magnitude
  // across a texel). The bounds leave 2-3x margin and sit well below what a
  // 4x coarser table gives (64x16: rms 2.3e-2, max 0.33, also in the ladder),
  // so a broken mapping or lookup fails here.
  const json& p = product("transmittance");
  const json& op = p["ladder"][p["operating_point"].get<size_t>()];
  EXPECT_EQ(op["settings"], json({{"size", {256, 64}}, {"steps", 6}}));
  EXPECT_LT(op["rms_rel"].get<double>(), 4e-3);
  EXPECT_LT(op["max_rel"].get<double>(), 5e-2);
  double coarse = 0;
  for (const json& q : p["ladder"])
    if (q["settings"]["size"] == json({64, 16}))
      coarse = std::max(coarse, q["rms_rel"].get<double>());
  EXPECT_GT(coarse, 4e-3) << "the bound would not catch a 4x coarser table";
}

void check_sky_radiance() {
  SCOPED_TRACE("check_sky_radiance");
  const json& sky = quick_earth().report["sky_radiance"];
  ASSERT_TRUE(sky.is_object());
  EXPECT_GT(sky["path_tracer"]["samples"].get<int>(), 0);
  ASSERT_EQ(sky["views"].size(), 3u * 3u * 8u);
  for (const json& v : sky["views"])
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(v["lut"][c].get<double>()));
      EXPECT_GT(v["path_traced"][c].get<double>(), 0.0);
      EXPECT_GT(v["path_traced_ci95"][c].get<double>(), 0.0);
      EXPECT_TRUE(std::isfinite(v["path_traced_ci95"][c].get<double>()));
      EXPECT_GT(v["quadrature_single"][c].get<double>(), 0.0);
    }
  for (const char* section :
       {"multiple", "converged_vs_path_tracer", "converged_relative_vs_path_tracer",
        "converged_angular_vs_path_tracer",
        "second_order_vs_path_tracer", "single_vs_path_tracer", "single_vs_quadrature"})
    for (const json& c : sky[section]["channels"]) {
      EXPECT_TRUE(std::isfinite(c["rel_rmse"].get<double>())) << section;
      EXPECT_TRUE(std::isfinite(c["noise_rel_rms"].get<double>())) << section;
    }
  // Single scattering from the tables against noise-free quadrature: the
  // tables' own error, small on Earth (measured 0.4 %).
  EXPECT_LT(sky["single_vs_quadrature"]["worst"]["rel_rmse"].get<double>(), 0.02);
  const std::string status = sky["target"]["status"];
  EXPECT_TRUE(status == "met" || status == "not met" || status == "undetermined") << status;
}

void check_bruneton() {
  SCOPED_TRACE("check_bruneton");
  const json& b = quick_earth().report["bruneton_comparison"];
  ASSERT_EQ(b["status"], "measured") << b.dump();
  EXPECT_GE(b["bruneton"]["orders_used"].get<int>(), 1);
  ASSERT_EQ(b["views"].size(), quick_earth().report["sky_radiance"]["views"].size());
  for (const json& v : b["views"])
    for (int c = 0; c < 3; ++c) EXPECT_GT(v["bruneton"][c].get<double>(), 0.0);
  for (const json& c : b["bruneton_vs_path_tracer"]["channels"])
    EXPECT_TRUE(std::isfinite(c["rel_rmse"].get<double>()));
}

void check_precision() {
  SCOPED_TRACE("check_precision");
  const json& precision = quick_earth().report["precision"];
  EXPECT_FALSE(precision["horizon_transmittance"]["rows"].empty());
  EXPECT_EQ(precision["half"].size(), 4u);
  for (const json& h : precision["half"])
    EXPECT_GE(h["half"]["max_rel"].get<double>(), 0.0) << h["product"];
}

void check_html() {
  SCOPED_TRACE("check_html");
  const std::string html = test::read_file(quick_earth().folder / "report.html");
  size_t svgs = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    ++svgs;
  EXPECT_EQ(svgs, 4u);
  EXPECT_NE(html.find("<img src=\"sky_preview.png\""), std::string::npos);
  // Entities are escaped once: no "&amp;ge;" for "≥".
  std::smatch m;
  EXPECT_FALSE(std::regex_search(html, m, std::regex("&amp;[a-z]+;"))) << m.str();
  // Prose holds numbers and words, not JSON: no objects, no bracketed lists
  // of numbers ({"size":[192,108],...}, [0.2588...,...]).
  EXPECT_EQ(html.find("{&quot;"), std::string::npos);
  EXPECT_EQ(html.find("{\""), std::string::npos);
  EXPECT_FALSE(std::regex_search(html, m, std::regex("\\[-?[0-9]"))) << m.str();
  // The multiscattering headline says where its largest error is.
  EXPECT_NE(html.find("multiscattering: the largest errors lie at the terminator"),
            std::string::npos);
  // A quick run marks no target as missed: it says it cannot judge them.
  EXPECT_EQ(html.find("class=\"notmet\""), std::string::npos);
  EXPECT_NE(html.find("A quick run (--quick) cannot judge the targets below"), std::string::npos);
}

void check_json_summary() {
  SCOPED_TRACE("check_json_summary");
  const json summary = json::parse(quick_earth().run.out);
  EXPECT_EQ(summary["ok"], true);
  ASSERT_EQ(summary["reports"].size(), 1u);
  const json& s = summary["reports"][0];
  EXPECT_EQ(s["scene"], "earth");
  EXPECT_EQ(s["products"].size(), 5u);  // four tables and the preview
  EXPECT_TRUE(s["sky_radiance"].is_object());
}

TEST(ReportCommand, QuickEarthReport) {
  const QuickEarth& r = quick_earth();
  ASSERT_EQ(r.run.exit_code, 0) << r.run.err;
  ASSERT_TRUE(r.report.is_object()) << "no report.json";
  check_files();
  check_ladders();
  check_error_falls();
  check_transmittance_accuracy();
  check_sky_radiance();
  check_bruneton();
  check_precision();
  check_html();
  check_json_summary();
}

TEST(ReportCommand, HelpNamesTheOptions) {
  const auto r = test::run_skybake({"report", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--only", "--quick", "--threads", "--json", "--paths", "--out"})
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
}

TEST(ReportCommand, UnknownProductIsAUsageErrorWithASuggestion) {
  const fs::path out = test::fresh_dir("report_usage");
  const auto r = test::run_skybake({"report", test::source_path("presets/earth.json").string(),
                                    "--only", "transmitance", "-o", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "skybake: error: --only: unknown product 'transmitance' (did you mean "
            "'transmittance'?)\n");
  EXPECT_TRUE(test::list_files(out).empty());
}

TEST(ReportCommand, NoiseProductsAreListedAsExact) {
  const fs::path out = test::fresh_dir("report_noise");
  const auto r = test::run_skybake(
      {"report", test::source_path("presets/clouds/horizon_zero_dawn.json").string(), "--quick",
       "-o", out.string(), "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json summary = json::parse(r.out);
  const json& products = summary["reports"][0]["products"];
  ASSERT_FALSE(products.empty());
  for (const json& p : products) EXPECT_EQ(p["kind"], "exact") << p["product"];
  EXPECT_TRUE(summary["reports"][0]["sky_radiance"].is_null());
}

TEST(ReportCommand, SkyLightProductsSayWhereTheyAreMeasured) {
  const fs::path out = test::fresh_dir("report_sky_light");
  const auto r = test::run_skybake(
      {"report", test::source_path("presets/earth_sky_light.json").string(), "--quick", "-o",
       out.string(), "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json summary = json::parse(r.out);
  std::map<std::string, std::string> kinds;
  for (const json& p : summary["reports"][0]["products"]) kinds[p["product"]] = p["kind"];
  EXPECT_EQ(kinds["sky_irradiance"], "section");
  EXPECT_EQ(kinds["sky_environment"], "not_measured");
  // The section the entry names is in report.json, with its target judged.
  const json report =
      json::parse(test::read_file(out / "earth_sky_light" / "report" / "report.json"));
  EXPECT_EQ(report["sky_irradiance"]["product"], "sky_irradiance");
  EXPECT_TRUE(report["sky_irradiance"]["target"].contains("status"));
}

}  // namespace
}  // namespace skybake

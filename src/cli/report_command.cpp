// skybake report: error against run time of every product of a scene
// (report/report.hpp). Loads every preset first (one bad preset stops the
// run before anything is measured), then writes DIR/<scene>/report/ for each
// and prints a summary table (or --json). Accuracy never changes the exit
// code: a report reports; only errors do (bad preset, usage, files).
#include <cstdio>
#include <iostream>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "pipeline/preset_loader.hpp"
#include "report/report.hpp"

namespace skybake::cli {

namespace {

std::string sci(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.2e}", v.get<double>()) : "-";
}

std::string percent(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.3g} %", 100.0 * v.get<double>()) : "-";
}

std::string settings_text(const nlohmann::json& settings) {
  std::string s;
  for (const auto& [key, value] : settings.items()) {
    std::string v;
    if (value.is_array())
      for (size_t i = 0; i < value.size(); ++i) v += (i ? "x" : "") + value[i].dump();
    else
      v = value.dump();
    s += (s.empty() ? "" : " ") + key + "=" + v;
  }
  return s;
}

void print_summary(const nlohmann::json& s) {
  std::printf("report %s (%s, %.1f s) -> %s\n", s["scene"].get<std::string>().c_str(),
              s["level"].get<std::string>().c_str(), s["seconds"].get<double>(),
              s["html"].get<std::string>().c_str());
  std::printf("  %-19s %-38s %9s %9s %9s %9s %6s\n", "product", "operating point", "seconds",
              "max rel", "rms rel", "half max", "points");
  for (const auto& p : s["products"]) {
    if (p["kind"] != "lut") {
      std::printf("  %-19s %s\n", p["product"].get<std::string>().c_str(),
                  p["kind"].get<std::string>().c_str());
      continue;
    }
    std::printf("  %-19s %-38s %9.4f %9s %9s %9s %6zu%s\n", p["product"].get<std::string>().c_str(),
                settings_text(p["operating_point"]).c_str(), p["seconds"].get<double>(),
                sci(p["max_rel"]).c_str(), sci(p["rms_rel"]).c_str(),
                sci(p["half_max_rel"]).c_str(), p["points"].get<size_t>(),
                p["on_pareto_front"].get<bool>() ? "" : "  (not on the Pareto front)");
  }
  const auto& sky = s["sky_radiance"];
  if (!sky.is_null()) {
    // A quick run's noisy references and small tables judge no missed
    // target (docs/report.md, `--quick`).
    std::string target = sky["target"];
    if (s["level"] == "quick" && target != "met") target = "not judged by a quick run";
    std::printf(
        "  sky radiance vs path tracer (%d paths): rel RMSE %s (%s without the reference noise "
        "of %s); 1%% daytime target: %s\n",
        sky["paths"].get<int>(), percent(sky["multiple_rel_rmse"]).c_str(),
        percent(sky["multiple_rel_rmse_denoised"]).c_str(), percent(sky["noise_rel_rms"]).c_str(),
        target.c_str());
    std::printf("  single scattering vs quadrature: rel RMSE %s\n",
                percent(sky["single_vs_quadrature_rel_rmse"]).c_str());
  }
  const auto& b = s["bruneton_comparison"];
  if (!b.is_null() && b["status"] == "measured")
    std::printf("  Hillaire vs Bruneton (%d orders) against the path tracer: rel RMSE %s vs %s\n",
                b["orders_used"].get<int>(), percent(b["hillaire_rel_rmse"]).c_str(),
                percent(b["bruneton_rel_rmse"]).c_str());
  else if (!b.is_null())
    std::printf("  Hillaire vs Bruneton: %s\n", b["status"].get<std::string>().c_str());
}

}  // namespace

int run_report(const ReportArgs& args) {
  const std::vector<Scene> scenes = load_scenes(expand_presets(args.presets));

  const size_t threads =
      args.threads > 0 ? size_t(args.threads) : size_t(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

  nlohmann::json reports = nlohmann::json::array();
  for (const Scene& scene : scenes) {
    ReportOptions options;
    options.out_dir = args.out_dir;
    options.products = args.only;
    options.quick = args.quick;
    options.path_samples = args.paths;
    if (!args.quiet)
      options.on_stage = [&scene](const std::string& stage) {
        std::fprintf(stderr, "report %s: %s\n", scene.name.c_str(), stage.c_str());
      };
    const nlohmann::json summary = report_summary(skybake::run_report(scene, options));
    if (!args.json) print_summary(summary);
    reports.push_back(summary);
  }
  if (args.json)
    std::cout << nlohmann::json{{"ok", true}, {"threads", threads}, {"reports", reports}}.dump(2)
              << "\n";
  return kExitOk;
}

}  // namespace skybake::cli

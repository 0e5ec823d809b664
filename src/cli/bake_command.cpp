// skybake bake: load and validate every preset first (so a bad one stops the
// run before anything is written), then bake each scene.
#include <cstdio>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/progress.hpp"
#include "core/error.hpp"
#include "farm/stamps.hpp"
#include "pipeline/bake.hpp"
#include "pipeline/preset_loader.hpp"

namespace skybake::cli {

namespace {

std::string files_string(const ManifestEntry& e, const std::string& scene_dir) {
  std::vector<std::string> names;
  for (const ManifestFile& f : e.files) names.push_back(f.path);
  return fmt::format("{}/{{{}}}", scene_dir, fmt::join(names, ","));
}

std::string shape_string(const ManifestEntry& e) {
  std::string s = fmt::format("{}", fmt::join(e.dimensions, "x"));
  if (e.layers > 1) s += fmt::format("[{}]", e.layers);
  return s;
}

nlohmann::json record_json(const OutputRecord& r, const std::string& scene_dir) {
  nlohmann::json files = nlohmann::json::array();
  for (const ManifestFile& f : r.entry.files)
    files.push_back({{"path", scene_dir + "/" + f.path}, {"format", f.format},
                     {"encoding", f.encoding}});
  return {{"product", r.product},       {"name", r.entry.name},
          {"status", r.status},         {"reason", r.reason},
          {"files", files},             {"dimensions", r.entry.dimensions},
          {"layers", r.entry.layers},   {"channels", r.entry.channels},
          {"input_hash", r.entry.input_hash}, {"bake_seconds", r.entry.bake_seconds},
          {"error_seconds", r.entry.error_seconds},
          {"estimated_error", r.entry.estimated_error}};
}

}  // namespace

int run_bake(const BakeArgs& args) {
  std::vector<Scene> scenes;
  for (const auto& preset : expand_presets(args.presets)) scenes.push_back(load_scene(preset));

  const size_t threads =
      args.threads > 0 ? size_t(args.threads) : size_t(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

  nlohmann::json report = {{"ok", true}, {"threads", threads}, {"scenes", nlohmann::json::array()}};
  ProgressLine progress(!args.quiet && !args.json);
  for (const Scene& scene : scenes) {
    BakeOptions options;
    options.out_dir = args.out_dir;
    options.only = args.only;
    options.force = args.force;
    options.on_recorded = update_stamp;
    options.on_progress = [&](const std::string& product, double f) {
      progress.update(scene.name + "/" + product, f);
    };
    const std::string scene_dir = (std::filesystem::path(args.out_dir) / scene.name).string();
    options.on_output = [&](const OutputRecord& r) {
      progress.clear();
      if (args.quiet || args.json) return;
      std::printf("%-10s %-18s %-12s %-40s %s\n", r.status == "baked" ? "baked" : "current",
                  r.product.c_str(), shape_string(r.entry).c_str(),
                  files_string(r.entry, scene_dir).c_str(),
                  r.status == "baked" ? fmt::format("{:.3f} s", r.entry.bake_seconds).c_str()
                                      : r.reason.c_str());
      std::fflush(stdout);
    };
    const BakeSummary summary = bake_scene(scene, options);
    progress.clear();
    nlohmann::json outputs = nlohmann::json::array();
    for (const OutputRecord& r : summary.outputs) outputs.push_back(record_json(r, scene_dir));
    report["scenes"].push_back({{"scene", scene.name},
                                {"preset", scene.file.string()},
                                {"folder", scene_dir},
                                {"outputs", outputs},
                                {"computed", summary.computed},
                                {"loaded", summary.loaded},
                                {"seconds", summary.seconds}});
  }
  if (args.json) std::cout << report.dump(2) << "\n";
  return kExitOk;
}

}  // namespace skybake::cli

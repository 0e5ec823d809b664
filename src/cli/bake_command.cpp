// skybake bake: load and validate every preset first (so a bad one stops the
// run before anything is written), then bake each scene.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/progress.hpp"
#include "core/error.hpp"
#include "farm/stamps.hpp"
#include "io/shader_constants.hpp"
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
          {"error", r.entry.error},     {"tiling", r.entry.tiling},
          {"warnings", r.entry.warnings}};
}

// The farm log of -v: timestamped lines on stderr (spdlog), off otherwise.
std::shared_ptr<spdlog::logger> make_log(bool verbose) {
  auto log = std::make_shared<spdlog::logger>(
      "skybake", std::make_shared<spdlog::sinks::stderr_sink_mt>());
  log->set_pattern("%Y-%m-%dT%H:%M:%S.%e skybake[%P] %v");
  log->set_level(verbose ? spdlog::level::info : spdlog::level::off);
  return log;
}

std::string names_or_none(const std::vector<std::string>& names) {
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

// The products a scene computed only to feed others (not written).
std::vector<std::string> computed_in_memory(const BakeSummary& s) {
  std::vector<std::string> out;
  for (const std::string& p : s.computed)
    if (std::none_of(s.outputs.begin(), s.outputs.end(),
                     [&](const OutputRecord& r) { return r.product == p && r.status == "baked"; }))
      out.push_back(p);
  return out;
}

// One `skybake bake`: every scene in turn, the line per output, the -v log,
// the summary line (or the --json document) at the end.
class BakeRun {
 public:
  BakeRun(const BakeArgs& args, size_t threads)
      : args_(args),
        progress_(!args.quiet && !args.json),
        log_(make_log(args.verbose)),
        report_({{"ok", true}, {"threads", threads}, {"scenes", nlohmann::json::array()}}) {}

  void bake(const Scene& scene) {
    const std::string scene_dir = (std::filesystem::path(args_.out_dir) / scene.name).string();
    log_->info("{}: {} -> {}", scene.name, scene.file.string(), scene_dir);
    const BakeSummary summary = bake_scene(scene, options_for(scene, scene_dir));
    progress_.clear();
    const nlohmann::json headers = emit_headers(summary);
    log_->info("{}: {:.3f} s; dependencies read back from disk: {}; computed in memory only: {}",
               scene.name, summary.seconds, names_or_none(summary.loaded),
               names_or_none(computed_in_memory(summary)));
    // On stderr whatever --quiet and --json say: a farm's log must show them.
    for (const std::string& w : summary.warnings)
      std::fprintf(stderr, "skybake: warning: %s/%s\n", scene.name.c_str(), w.c_str());
    warnings_ += summary.warnings.size();
    nlohmann::json scene_report = scene_json(scene, summary, scene_dir);
    if (args_.emit_shader_constants) scene_report["shader_constants"] = headers;
    report_["scenes"].push_back(std::move(scene_report));
  }

  // The summary line, or the --json document with the same numbers.
  void finish(double seconds) {
    if (args_.json) {
      report_["summary"] = {{"baked", baked_},
                            {"up_to_date", up_to_date_},
                            {"warnings", warnings_},
                            {"seconds", seconds}};
      std::cout << report_.dump(2) << "\n";
    } else if (!args_.quiet) {
      std::printf("skybake: %zu baked, %zu up to date, %zu warning%s, %.2f s\n", baked_,
                  up_to_date_, warnings_, warnings_ == 1 ? "" : "s", seconds);
    }
  }

  spdlog::logger& log() { return *log_; }
  size_t warnings() const { return warnings_; }

 private:
  BakeOptions options_for(const Scene& scene, const std::string& scene_dir) {
    BakeOptions options;
    options.out_dir = args_.out_dir;
    options.only = args_.only;
    options.force = args_.force;
    options.verify = args_.verify;
    options.on_recorded = update_stamp;
    options.on_progress = [this, &scene](const std::string& product, double f) {
      progress_.update(scene.name + "/" + product, f);
    };
    options.on_output = [this, &scene, scene_dir](const OutputRecord& r) {
      progress_.clear();
      (r.status == "baked" ? baked_ : up_to_date_) += 1;
      log_output(scene, r);
      if (!args_.quiet && !args_.json) print_output(r, scene_dir);
    };
    return options;
  }

  // --emit-shader-constants: the headers of every output of the run, baked or
  // current, from the manifest the bake just wrote.
  nlohmann::json emit_headers(const BakeSummary& summary) {
    nlohmann::json paths = nlohmann::json::array();
    if (!args_.emit_shader_constants) return paths;
    std::vector<std::string> names;
    for (const OutputRecord& r : summary.outputs) names.push_back(r.entry.name);
    for (const auto& path :
         emit_shader_constants(summary.scene_dir, names, "skybake " SKYBAKE_VERSION)) {
      log_->info("{}: wrote {}", summary.scene, path.string());
      paths.push_back(path.string());
    }
    return paths;
  }

  void log_output(const Scene& scene, const OutputRecord& r) {
    if (r.status == "baked")
      log_->info("{}/{}: baked in {:.3f} s ({})", scene.name, r.product, r.entry.bake_seconds,
                 r.reason);
    else
      log_->info("{}/{}: {}", scene.name, r.product, r.reason);
  }

  static void print_output(const OutputRecord& r, const std::string& scene_dir) {
    std::printf("%-10s %-18s %-12s %-40s %s\n", r.status == "baked" ? "baked" : "current",
                r.product.c_str(), shape_string(r.entry).c_str(),
                files_string(r.entry, scene_dir).c_str(),
                r.status == "baked" ? fmt::format("{:.3f} s", r.entry.bake_seconds).c_str()
                                    : r.reason.c_str());
    std::fflush(stdout);
  }

  static nlohmann::json scene_json(const Scene& scene, const BakeSummary& summary,
                                   const std::string& scene_dir) {
    nlohmann::json outputs = nlohmann::json::array();
    for (const OutputRecord& r : summary.outputs) outputs.push_back(record_json(r, scene_dir));
    return {{"scene", scene.name},         {"preset", scene.file.string()},
            {"folder", scene_dir},         {"outputs", outputs},
            {"computed", summary.computed}, {"loaded", summary.loaded},
            {"warnings", summary.warnings}, {"seconds", summary.seconds}};
  }

  const BakeArgs& args_;
  ProgressLine progress_;
  std::shared_ptr<spdlog::logger> log_;
  nlohmann::json report_;
  size_t baked_ = 0, up_to_date_ = 0, warnings_ = 0;
};

}  // namespace

int run_bake(const BakeArgs& args) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Scene> scenes = load_scenes(expand_presets(args.presets));

  const size_t threads =
      args.threads > 0 ? size_t(args.threads) : size_t(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

  BakeRun run(args, threads);
  run.log().info("bake {} scene{} into {} with {} thread{}{}", scenes.size(),
                 scenes.size() == 1 ? "" : "s", args.out_dir, threads, threads == 1 ? "" : "s",
                 args.force ? ", --force" : "");
  for (const Scene& scene : scenes) run.bake(scene);
  run.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  // --strict: the files are written and recorded; the warnings fail the run.
  return args.strict && run.warnings() > 0 ? kExitFailure : kExitOk;
}

}  // namespace skybake::cli

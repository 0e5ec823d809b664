// skybake plan: the product graph without baking anything. For each scene:
// what is requested, what is only computed as a dependency, sizes, formats,
// files and whether each output is current (with the reason). Over a whole
// catalog (files, folders, globs) it also gives the farm graph of stale nodes,
// as JSON or emitted as a ninja file or a Slurm batch script.
#include <cstdio>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/bake_log.hpp"
#include "io/manifest.hpp"
#include "farm/catalog.hpp"
#include "farm/emit.hpp"
#include "farm/farm_graph.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"

namespace fs = std::filesystem;

namespace skybake::cli {

namespace {

nlohmann::json scene_plan(const Scene& scene, const PlanArgs& args, bool print) {
  const ProductGraph graph = build_product_graph(scene, args.only);
  const fs::path dir = fs::path(args.out_dir) / scene.name;
  const Manifest manifest = read_manifest(dir / "manifest.json");
  const BakeLog log = read_bake_log(dir / "bake_log.json");
  nlohmann::json nodes = nlohmann::json::array();
  if (print)
    std::printf("scene %s (%s) -> %s\n", scene.name.c_str(), scene.file.c_str(),
                dir.string().c_str());
  for (const GraphNode& node : graph.nodes) {
    std::vector<std::string> deps;
    for (size_t d : node.deps) deps.push_back(graph.nodes[d].info->name);
    const Freshness fresh = node.requested ? check_freshness(node, manifest, dir, {&log, false})
                                           : Freshness{false, "dependency, computed in memory"};
    const std::vector<std::string> files =
        node.requested ? output_files(node.spec) : std::vector<std::string>{};
    nodes.push_back({{"product", node.info->name},
                     {"name", node.spec.name},
                     {"requested", node.requested},
                     {"size", node.spec.size},
                     {"formats", node.spec.formats},
                     {"precision", node.spec.precision},
                     {"files", files},
                     {"dependencies", deps},
                     {"input_hash", node.input_hash},
                     {"up_to_date", fresh.current},
                     {"reason", fresh.reason}});
    if (print)
      std::printf("  %-18s %-10s %-12s %-14s reads [%s]  %s\n", node.info->name.c_str(),
                  node.requested ? "write" : "in memory",
                  fmt::format("{}", fmt::join(node.spec.size, "x")).c_str(),
                  fmt::format("{}", fmt::join(node.spec.formats, ",")).c_str(),
                  fmt::format("{}", fmt::join(deps, ", ")).c_str(), fresh.reason.c_str());
  }
  return {{"scene", scene.name}, {"preset", scene.file.string()}, {"folder", dir.string()},
          {"nodes", nodes}};
}

void write_or_print(const std::string& text, const std::string& file) {
  if (file.empty() || file == "-") {
    std::cout << text;
    return;
  }
  // The folder it names may not exist yet (a fresh build tree).
  const fs::path parent = fs::path(file).parent_path();
  if (!parent.empty()) create_folder(parent);
  write_text_atomic(file, text);
}

// The ninja file or Slurm script of the stale nodes, on stdout or --emit-file.
int emit_plan(const std::vector<Scene>& scenes, const PlanArgs& args) {
  if (!args.only.empty()) throw UsageError("--emit plans whole scenes; drop --only");
  if (args.emit == "slurm" && !args.launcher.empty())
    throw UsageError("--launcher applies to --emit ninja only");
  // A job-array task bakes whole presets: its unit is always the scene.
  if (args.emit == "slurm" && args.edges == "product")
    throw UsageError("--edges product applies to --emit ninja only; a slurm array task bakes "
                     "whole presets (--chunk of them)");
  if (args.edges == "product" && args.chunk > 1)
    throw UsageError("--chunk groups scenes; with --edges product every edge is one product");
  const FarmGraph farm = build_farm_graph(scenes, args.out_dir);
  EmitOptions opt;
  opt.skybake = args.self;
  opt.launcher = args.launcher;
  opt.threads = args.threads;
  opt.chunk = args.chunk;
  opt.max_parallel = args.max_parallel;
  opt.strict = args.strict;
  opt.edges = args.edges == "product" ? NinjaEdges::kProduct : NinjaEdges::kScene;
  write_or_print(args.emit == "ninja" ? emit_ninja(farm, opt) : emit_slurm(farm, opt),
                 args.emit_file);
  if (!args.emit_file.empty() && args.emit_file != "-")
    std::fprintf(stderr, "wrote %s (%zu products of %zu scenes)\n", args.emit_file.c_str(),
                 farm.nodes.size(), scenes.size());
  return kExitOk;
}

}  // namespace

int run_plan(const PlanArgs& args) {
  if (fs::is_regular_file(args.out_dir))
    throw UsageError(fmt::format(
        "-o: '{}' is a file; -o names the output folder (the emitted file is --emit-file)",
        args.out_dir));
  const std::vector<Scene> scenes = load_scenes(expand_presets(args.catalog));
  if (!args.emit.empty()) return emit_plan(scenes, args);

  nlohmann::json plans = nlohmann::json::array();
  for (const Scene& scene : scenes) plans.push_back(scene_plan(scene, args, !args.json));
  if (args.json) {
    nlohmann::json j = args.only.empty() ? farm_graph_json(build_farm_graph(scenes, args.out_dir))
                                         : nlohmann::json::object();
    j["scenes"] = plans;
    std::cout << j.dump(2) << "\n";
  }
  return kExitOk;
}

}  // namespace skybake::cli

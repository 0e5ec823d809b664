#include "farm/farm_graph.hpp"

#include <map>

#include <fmt/format.h>

#include "core/error.hpp"
#include "farm/stamps.hpp"
#include "io/bake_log.hpp"
#include "io/manifest.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product_graph.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

double estimate_seconds(const GraphNode& node) {
  double texels = 1.0;
  for (int s : node.spec.size) texels *= s;
  return texels * node.info->ns_per_texel * 1e-9;
}

}  // namespace

FarmGraph build_farm_graph(const std::vector<Scene>& scenes, const fs::path& out_dir) {
  FarmGraph farm;
  farm.out_dir = out_dir;
  std::map<std::string, std::string> preset_of_scene;
  for (const Scene& scene : scenes) {
    auto [it, fresh] = preset_of_scene.emplace(scene.name, scene.file.string());
    if (!fresh)
      throw UsageError(fmt::format("scenes of {} and {} are both named '{}': their outputs would "
                                   "share {}/{}",
                                   it->second, scene.file.string(), scene.name, out_dir.string(),
                                   scene.name));
    const ProductGraph graph = build_product_graph(scene, {});
    const fs::path scene_dir = out_dir / scene.name;
    const Manifest manifest = read_manifest(scene_dir / "manifest.json");
    const BakeLog log = read_bake_log(scene_dir / "bake_log.json");
    std::vector<double> cost(graph.nodes.size(), 0.0);
    for (size_t i = 0; i < graph.nodes.size(); ++i) {
      const GraphNode& node = graph.nodes[i];
      cost[i] = estimate_seconds(node);
      std::vector<std::string> deps;
      for (size_t d : node.deps) {
        if (graph.nodes[d].requested)
          deps.push_back(scene.name + "/" + graph.nodes[d].spec.name);
        else
          cost[i] += cost[d];  // computed in memory by this task
      }
      if (!node.requested) continue;
      FarmNode f;
      f.id = scene.name + "/" + node.spec.name;
      f.preset = scene.file.string();
      for (const fs::path& s : scene.sources) f.sources.push_back(s.string());
      f.scene = scene.name;
      f.product = node.info->name;
      f.input_hash = node.input_hash;
      for (const std::string& file : output_files(node.spec))
        f.files.push_back((fs::path(scene.name) / file).string());
      f.stamp = stamp_path(fs::path(scene.name), node.spec.name).string();
      f.estimated_seconds = cost[i];
      f.deps = deps;
      const Freshness fresh = check_freshness(node, manifest, scene_dir, {&log, false});
      f.current = fresh.current;
      f.reason = fresh.reason;
      farm.nodes.push_back(std::move(f));
    }
  }
  return farm;
}

nlohmann::json farm_graph_json(const FarmGraph& graph) {
  std::map<std::string, bool> stale;
  for (const FarmNode& n : graph.nodes) stale[n.id] = !n.current;
  nlohmann::json nodes = nlohmann::json::array(), edges = nlohmann::json::array();
  for (const FarmNode& n : graph.nodes) {
    if (n.current) continue;
    std::vector<std::string> deps;
    for (const std::string& d : n.deps)
      if (stale[d]) {
        deps.push_back(d);
        edges.push_back({d, n.id});
      }
    nodes.push_back({{"id", n.id},
                     {"preset", n.preset},
                     {"scene", n.scene},
                     {"product", n.product},
                     {"input_hash", n.input_hash},
                     {"outputs", n.files},
                     {"estimated_seconds", n.estimated_seconds},
                     {"dependencies", deps},
                     {"reason", n.reason},
                     {"command", {"skybake", "bake", n.preset, "--only", n.product, "-o",
                                  graph.out_dir.string()}}});
  }
  return {{"out_dir", graph.out_dir.string()}, {"nodes", nodes}, {"edges", edges}};
}

}  // namespace skybake

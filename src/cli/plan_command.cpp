// skybake plan: the product graph of each scene without baking anything:
// what is requested, what is only computed as a dependency, sizes, formats,
// files and whether each output is current (with the reason).
#include <cstdio>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/manifest.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake::cli {

int run_plan(const PlanArgs& args) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const std::string& preset : args.presets) {
    const Scene scene = load_scene(preset);
    const ProductGraph graph = build_product_graph(scene, args.only);
    const std::filesystem::path dir = std::filesystem::path(args.out_dir) / scene.name;
    const Manifest manifest = read_manifest(dir / "manifest.json");
    nlohmann::json nodes = nlohmann::json::array();
    if (!args.json) std::printf("scene %s (%s) -> %s\n", scene.name.c_str(), preset.c_str(),
                                dir.string().c_str());
    for (const GraphNode& node : graph.nodes) {
      std::vector<std::string> deps;
      for (size_t d : node.deps) deps.push_back(graph.nodes[d].info->name);
      const Freshness fresh = node.requested ? check_freshness(node, manifest, dir)
                                             : Freshness{false, "dependency, not written"};
      const std::vector<std::string> files = node.requested ? output_files(node.spec)
                                                            : std::vector<std::string>{};
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
      if (!args.json)
        std::printf("  %-18s %-10s %-12s %-16s deps [%s]  %s\n", node.info->name.c_str(),
                    node.requested ? "write" : "in memory",
                    fmt::format("{}", fmt::join(node.spec.size, "x")).c_str(),
                    fmt::format("{}", fmt::join(node.spec.formats, ",")).c_str(),
                    fmt::format("{}", fmt::join(deps, ", ")).c_str(), fresh.reason.c_str());
    }
    scenes.push_back({{"scene", scene.name}, {"preset", preset}, {"folder", dir.string()},
                      {"nodes", nodes}});
  }
  if (args.json) std::cout << nlohmann::json{{"scenes", scenes}}.dump(2) << "\n";
  return kExitOk;
}

}  // namespace skybake::cli

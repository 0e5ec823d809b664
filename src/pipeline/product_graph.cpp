#include "pipeline/product_graph.hpp"

#include <algorithm>
#include <functional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "core/suggest.hpp"

namespace skybake {

const GraphNode* ProductGraph::find(const std::string& product) const {
  for (const GraphNode& n : nodes)
    if (n.info->name == product) return &n;
  return nullptr;
}

OutputSpec default_spec(const ProductInfo& info) {
  OutputSpec spec;
  spec.product = info.name;
  spec.name = info.name;
  spec.size = info.default_size;
  spec.formats = {};
  spec.options = nlohmann::json::object({{"product", info.name}});
  return spec;
}

namespace {

// Raised whenever what a file holds for the same texels changes.
constexpr const char* kFileLayout =
    "file layout 4: typed metadata, exact atlas, EXR and VDB compression per product, "
    "uncompressed EXR atmosphere tables";

// Keys of an output object read only by the file writers.
bool is_writer_key(const std::string& key) {
  return key == "exr_compression" || key == "dds_header" || key == "grid_names" ||
         key == "vdb_compression";
}

// Keys of an output object that shape files or the manifest's record but not
// texture values (max_error decides a warning: its output is recorded again,
// its dependents are not).
bool is_file_key(const std::string& key) {
  return key == "name" || key == "formats" || key == "precision" || key == "dds_format" ||
         key == "ktx2_format" || key == "preview" || key == "mips" || key == "max_error";
}

void compute_hashes(const Scene& scene, GraphNode& node, const std::vector<GraphNode>& nodes) {
  Hasher value;
  value.add("skybake " SKYBAKE_VERSION).add(node.info->name);
  for (const std::string& section : node.info->scene_sections) {
    auto it = scene.resolved.find(section);
    value.add(section).add(it == scene.resolved.end() ? std::string("null") : it->dump());
  }
  // A spectral bake (docs/presets.md "Spectral skies") changes every table
  // that reads the atmosphere; without one the hash is the RGB bake's.
  const auto& sections = node.info->scene_sections;
  if (std::find(sections.begin(), sections.end(), "atmosphere") != sections.end())
    if (auto it = scene.resolved.find("spectral"); it != scene.resolved.end())
      value.add("spectral").add(it->dump());
  for (int s : node.spec.size) value.add(std::to_string(s));
  nlohmann::json values = nlohmann::json::object();
  nlohmann::json files = nlohmann::json::object();
  for (auto& [key, v] : node.spec.options.items())
    (is_file_key(key) || is_writer_key(key) ? files : values)[key] = v;
  value.add(values.dump());
  for (size_t d : node.deps) value.add(nodes[d].value_hash);
  node.value_hash = value.hex();

  Hasher input;
  input.add(node.value_hash).add(files.dump()).add(node.spec.name).add(node.spec.precision);
  // The files' layout (docs/formats.md: attribute types, the atlas shape):
  // files of another layout are not current, and their metadata is not read.
  input.add(kFileLayout);
  for (const std::string& f : node.spec.formats) input.add(f);
  node.input_hash = input.hex();
}

}  // namespace

ProductGraph build_product_graph(const Scene& scene, const std::vector<std::string>& only) {
  for (const std::string& name : only) {
    if (!find_product(name))
      throw UsageError(
          fmt::format("--only: unknown product '{}'{}", name, did_you_mean(name, product_names())));
    if (!scene.find_output(name)) {
      std::vector<std::string> asked;
      for (const OutputSpec& o : scene.outputs) asked.push_back(o.product);
      throw UsageError(fmt::format("--only: scene '{}' ({}) does not request '{}'; it requests: {}",
                                   scene.name, scene.file.string(), name, fmt::join(asked, ", ")));
    }
  }
  auto wanted = [&](const std::string& product) {
    return only.empty() || std::find(only.begin(), only.end(), product) != only.end();
  };

  ProductGraph graph;
  std::vector<int> state(product_registry().size(), 0);  // 0 new, 1 visiting, 2 done
  std::vector<std::string> stack;
  // Depth-first, dependencies first; a cycle is a registry bug and is reported with its path.
  std::function<size_t(const ProductInfo&, bool)> visit = [&](const ProductInfo& info,
                                                              bool requested) -> size_t {
    const size_t id = size_t(&info - product_registry().data());
    stack.push_back(info.name);
    if (state[id] == 1)
      throw Error(fmt::format("product dependency cycle: {}", fmt::join(stack, " -> ")));
    if (state[id] == 2) {
      stack.pop_back();
      for (size_t i = 0; i < graph.nodes.size(); ++i)
        if (graph.nodes[i].info == &info) {
          graph.nodes[i].requested |= requested;
          return i;
        }
    }
    state[id] = 1;
    std::vector<size_t> deps;
    for (const std::string& dep : info.dependencies) {
      const ProductInfo* d = find_product(dep);
      if (!d) throw Error(fmt::format("product '{}' depends on unknown '{}'", info.name, dep));
      deps.push_back(visit(*d, false));
    }
    GraphNode node;
    node.info = &info;
    const OutputSpec* asked = scene.find_output(info.name);
    node.spec = asked ? *asked : default_spec(info);
    node.requested = requested;
    node.deps = deps;
    compute_hashes(scene, node, graph.nodes);
    graph.nodes.push_back(std::move(node));
    state[id] = 2;
    stack.pop_back();
    return graph.nodes.size() - 1;
  };

  for (const OutputSpec& out : scene.outputs) {
    if (!wanted(out.product)) continue;
    const ProductInfo* info = find_product(out.product);
    if (!info) throw Error(fmt::format("unknown product '{}' passed validation", out.product));
    visit(*info, true);
  }
  return graph;
}

}  // namespace skybake

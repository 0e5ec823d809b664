#include "pipeline/bake.hpp"

#include <chrono>
#include <optional>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product_graph.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

ManifestEntry make_entry(const GraphNode& node, const Texture& tex,
                         std::vector<ManifestFile> files, double seconds) {
  ManifestEntry e;
  e.product = node.info->name;
  e.name = node.spec.name;
  e.files = std::move(files);
  e.dimensions = {tex.width, tex.height};
  if (tex.depth > 1) e.dimensions.push_back(tex.depth);
  e.layers = tex.layers;
  e.channels = tex.channels;
  for (const auto& [key, value] : tex.metadata) e.metadata[key] = value;
  e.input_hash = node.input_hash;
  e.bake_seconds = seconds;
  return e;
}

}  // namespace

BakeSummary bake_scene(const Scene& scene, const BakeOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const ProductGraph graph = build_product_graph(scene, options.only);
  BakeSummary summary;
  summary.scene = scene.name;
  summary.scene_dir = options.out_dir / scene.name;

  std::error_code ec;
  fs::create_directories(summary.scene_dir, ec);
  if (ec)
    throw IoError(fmt::format("{}: cannot create folder: {}", summary.scene_dir.string(),
                              ec.message()));

  const fs::path manifest_path = summary.scene_dir / "manifest.json";
  const Manifest before = read_manifest(manifest_path);

  // Stale requested nodes, then everything they read (reverse topological order).
  const size_t n = graph.nodes.size();
  std::vector<char> stale(n, 0), needed(n, 0);
  std::vector<std::string> reasons(n);
  for (size_t i = 0; i < n; ++i) {
    const GraphNode& node = graph.nodes[i];
    if (!node.requested) continue;
    const Freshness f = check_freshness(node, before, summary.scene_dir);
    stale[i] = options.force || !f.current;
    reasons[i] = options.force && f.current ? "forced" : f.reason;
    needed[i] = stale[i];
  }
  for (size_t i = n; i-- > 0;)
    if (needed[i])
      for (size_t d : graph.nodes[i].deps) needed[d] = 1;

  std::vector<std::optional<Texture>> textures(n);
  std::vector<ManifestEntry> written;
  for (size_t i = 0; i < n; ++i) {
    const GraphNode& node = graph.nodes[i];
    if (!needed[i]) {
      if (node.requested) {
        OutputRecord rec{node.info->name, "up to date", reasons[i],
                         before.entries.at(node.spec.name)};
        if (options.on_output) options.on_output(rec);
        summary.outputs.push_back(std::move(rec));
      }
      continue;
    }
    ProductInputs inputs;
    for (size_t d : node.deps) inputs[graph.nodes[d].info->name] = &*textures[d];
    BakeContext ctx;
    if (options.on_progress) {
      const std::string product = node.info->name;
      ctx.on_progress = [&options, product](double f) { options.on_progress(product, f); };
    }
    const auto t_bake = std::chrono::steady_clock::now();
    textures[i] = node.info->bake(scene, node.spec, inputs, ctx);
    Texture& tex = *textures[i];
    set_meta(tex.metadata, "product", node.info->name);
    set_meta(tex.metadata, "tool", std::string("skybake " SKYBAKE_VERSION));
    set_meta(tex.metadata, "input_hash", node.input_hash);
    set_meta(tex.metadata, "preset", scene.file.filename().string());
    summary.computed.push_back(node.info->name);
    if (!stale[i]) continue;
    std::vector<ManifestFile> files = write_outputs(tex, *node.info, node.spec, summary.scene_dir);
    OutputRecord rec{node.info->name, "baked", reasons[i],
                     make_entry(node, tex, std::move(files), seconds_since(t_bake))};
    written.push_back(rec.entry);
    if (options.on_output) options.on_output(rec);
    summary.outputs.push_back(std::move(rec));
  }

  if (!written.empty()) {
    // Re-read under the lock: another bake may have added entries meanwhile.
    DirectoryLock lock(summary.scene_dir);
    Manifest m = read_manifest(manifest_path);
    m.scene = scene.name;
    m.preset = scene.file.string();
    m.tool_version = SKYBAKE_VERSION;
    for (const ManifestEntry& e : written) m.entries[e.name] = e;
    write_manifest(manifest_path, m);
  }
  summary.seconds = seconds_since(t0);
  return summary;
}

}  // namespace skybake

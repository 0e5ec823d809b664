#include "pipeline/bake.hpp"

#include <chrono>
#include <exception>
#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/texture_file.hpp"
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

// A requested dependency that is current on disk is read back instead of
// recomputed (so `bake --only X` reads X's inputs baked by another node), but
// only from a lossless file: float EXR or R32G32B32A32_FLOAT DDS store the
// float32 values bit-exactly, so dependents come out identical either way.
std::optional<Texture> load_current_output(const ManifestEntry& entry, const fs::path& dir) {
  for (const ManifestFile& f : entry.files) {
    try {
      if (f.format == "exr" && f.encoding == "float") {
        Texture tex = read_texture_file((dir / f.path).string()).texture;
        if (tex.channels == entry.channels) return tex;
      }
      if (f.format == "dds" && f.encoding == "R32G32B32A32_FLOAT") {
        Texture tex = read_texture_file((dir / f.path).string()).texture;
        if (tex.channel_count() < int(entry.channels.size())) continue;
        // The DDS holds RGBA; keep the channels the product has.
        Texture trimmed(tex.width, tex.height, tex.depth, tex.layers, entry.channels);
        const size_t nc = entry.channels.size(), nd = size_t(tex.channel_count());
        for (size_t t = 0; t < tex.texel_count(); ++t)
          for (size_t c = 0; c < nc; ++c) trimmed.data[t * nc + c] = tex.data[t * nd + c];
        for (const auto& [k, v] : entry.metadata.items())
          trimmed.metadata[k] = v.is_string() ? v.get<std::string>() : v.dump();
        return trimmed;
      }
    } catch (const Error&) {
      // Unreadable: fall back to baking it again.
    }
  }
  return std::nullopt;
}

}  // namespace

void update_stamp(const fs::path& scene_dir, const std::string& name, const std::string& hash) {
  const fs::path stamp = stamp_path(scene_dir, name);
  std::error_code ec;
  fs::create_directories(stamp.parent_path(), ec);
  std::ifstream in(stamp);
  std::string old;
  std::getline(in, old);
  if (old == hash) return;  // untouched, so ninja's restat sees no change
  write_text_atomic(stamp, hash + "\n");
}

fs::path stamp_path(const fs::path& scene_dir, const std::string& name) {
  return scene_dir / ".stamps" / (name + ".stamp");
}

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
  std::exception_ptr failure;  // a product that failed; what was written before stays recorded
  for (size_t i = 0; i < n && !failure; ++i) try {
    const GraphNode& node = graph.nodes[i];
    if (!needed[i]) {
      if (node.requested) {
        update_stamp(summary.scene_dir, node.spec.name, node.input_hash);
        OutputRecord rec{node.info->name, "up to date", reasons[i],
                         before.entries.at(node.spec.name)};
        if (options.on_output) options.on_output(rec);
        summary.outputs.push_back(std::move(rec));
      }
      continue;
    }
    // A dependency the scene writes and that is current on disk is read back
    // (also under --only, where it is not requested in this run).
    if (!stale[i] && scene.find_output(node.info->name) &&
        check_freshness(node, before, summary.scene_dir).current) {
      textures[i] = load_current_output(before.entries.at(node.spec.name), summary.scene_dir);
      if (textures[i]) {
        summary.loaded.push_back(node.info->name);
        if (node.requested) {
          update_stamp(summary.scene_dir, node.spec.name, node.input_hash);
          OutputRecord rec{node.info->name, "up to date", reasons[i],
                           before.entries.at(node.spec.name)};
          if (options.on_output) options.on_output(rec);
          summary.outputs.push_back(std::move(rec));
        }
        continue;
      }
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
    if (!node.requested) continue;
    const double bake_seconds = seconds_since(t_bake);
    std::vector<ManifestFile> files = write_outputs(tex, *node.info, node.spec, summary.scene_dir);
    OutputRecord rec{node.info->name, "baked", reasons[i],
                     make_entry(node, tex, std::move(files), bake_seconds)};
    if (node.info->estimate_error) {
      const auto t_estimate = std::chrono::steady_clock::now();
      rec.entry.estimated_error = node.info->estimate_error(scene, node.spec, inputs, tex);
      rec.entry.estimated_error["seconds"] = seconds_since(t_estimate);
    }
    written.push_back(rec.entry);
    if (options.on_output) options.on_output(rec);
    summary.outputs.push_back(std::move(rec));
  } catch (...) {
    failure = std::current_exception();
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
  // Stamps after the manifest: a stamp never claims an output the manifest
  // does not list (a process killed in between leaves the stamp old, so
  // ninja runs the edge again and skybake finds the output current).
  for (const ManifestEntry& e : written) update_stamp(summary.scene_dir, e.name, e.input_hash);
  if (failure) std::rethrow_exception(failure);
  summary.seconds = seconds_since(t0);
  return summary;
}

}  // namespace skybake

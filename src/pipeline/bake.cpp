#include "pipeline/bake.hpp"

#include <chrono>
#include <exception>
#include <optional>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/output_readback.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product_graph.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
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

// One bake of one scene, in stages: decide what is stale, then for each node
// in dependency order report it current, read it back, or compute (and write)
// it; finally merge what was written into the manifest.
class SceneBake {
 public:
  SceneBake(const Scene& scene, const BakeOptions& options)
      : scene_(scene), options_(options), graph_(build_product_graph(scene, options.only)) {
    summary_.scene = scene.name;
    summary_.scene_dir = options.out_dir / scene.name;
  }

  BakeSummary run() {
    const auto t0 = Clock::now();
    create_scene_dir();
    before_ = read_manifest(manifest_path());
    mark_stale();
    std::exception_ptr failure;  // what was written before a failure stays recorded
    for (size_t i = 0; i < graph_.nodes.size() && !failure; ++i) try {
        visit(i);
      } catch (...) {
        failure = std::current_exception();
      }
    record_written();
    if (failure) std::rethrow_exception(failure);
    summary_.seconds = seconds_since(t0);
    return std::move(summary_);
  }

 private:
  fs::path manifest_path() const { return summary_.scene_dir / "manifest.json"; }

  void create_scene_dir() const {
    std::error_code ec;
    fs::create_directories(summary_.scene_dir, ec);
    if (ec)
      throw IoError(fmt::format("{}: cannot create folder: {}", summary_.scene_dir.string(),
                                ec.message()));
  }

  // Stale requested nodes, then everything they read (reverse topological order).
  void mark_stale() {
    const size_t n = graph_.nodes.size();
    stale_.assign(n, 0);
    needed_.assign(n, 0);
    reasons_.assign(n, "");
    textures_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const GraphNode& node = graph_.nodes[i];
      if (!node.requested) continue;
      const Freshness f = check_freshness(node, before_, summary_.scene_dir);
      stale_[i] = options_.force || !f.current;
      reasons_[i] = options_.force && f.current ? "forced" : f.reason;
      needed_[i] = stale_[i];
    }
    for (size_t i = n; i-- > 0;)
      if (needed_[i])
        for (size_t d : graph_.nodes[i].deps) needed_[d] = 1;
  }

  void visit(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    if (!needed_[i]) {
      if (node.requested) report_current(i);
      return;
    }
    if (read_back(i)) {
      if (node.requested) report_current(i);
      return;
    }
    compute(i);
    if (node.requested) write(i);
  }

  // A requested output found current: recorded as it is in the manifest.
  void report_current(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    if (options_.on_recorded)
      options_.on_recorded(summary_.scene_dir, node.spec.name, node.input_hash);
    OutputRecord rec{node.info->name, "up to date", reasons_[i],
                     before_.entries.at(node.spec.name)};
    if (options_.on_output) options_.on_output(rec);
    summary_.outputs.push_back(std::move(rec));
  }

  // A dependency the scene writes and that is current on disk is read back
  // (also under --only, where it is not requested in this run).
  bool read_back(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    if (stale_[i] || !scene_.find_output(node.info->name) ||
        !check_freshness(node, before_, summary_.scene_dir).current)
      return false;
    textures_[i] = read_lossless_output(before_.entries.at(node.spec.name), summary_.scene_dir);
    if (textures_[i]) summary_.loaded.push_back(node.info->name);
    return textures_[i].has_value();
  }

  void compute(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    ProductInputs inputs = inputs_of(node);
    BakeContext ctx;
    if (options_.on_progress) {
      const std::string product = node.info->name;
      const auto& report = options_.on_progress;
      ctx.on_progress = [&report, product](double f) { report(product, f); };
    }
    const auto t_bake = Clock::now();
    textures_[i] = node.info->bake(scene_, node.spec, inputs, ctx);
    bake_seconds_ = seconds_since(t_bake);
    Texture& tex = *textures_[i];
    set_meta(tex.metadata, "product", node.info->name);
    set_meta(tex.metadata, "tool", std::string("skybake " SKYBAKE_VERSION));
    set_meta(tex.metadata, "input_hash", node.input_hash);
    set_meta(tex.metadata, "preset", scene_.file.filename().string());
    summary_.computed.push_back(node.info->name);
  }

  ProductInputs inputs_of(const GraphNode& node) const {
    ProductInputs inputs;
    for (size_t d : node.deps) inputs[graph_.nodes[d].info->name] = &*textures_[d];
    return inputs;
  }

  // Writes a computed output's files and measures its error estimate.
  void write(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    const Texture& tex = *textures_[i];
    std::vector<ManifestFile> files = write_outputs(tex, *node.info, node.spec, summary_.scene_dir);
    OutputRecord rec{node.info->name, "baked", reasons_[i],
                     make_entry(node, tex, std::move(files), bake_seconds_)};
    if (node.info->estimate_error) {
      const auto t_estimate = Clock::now();
      rec.entry.estimated_error = node.info->estimate_error(scene_, node.spec, inputs_of(node), tex);
      rec.entry.estimated_error["seconds"] = seconds_since(t_estimate);
    }
    written_.push_back(rec.entry);
    if (options_.on_output) options_.on_output(rec);
    summary_.outputs.push_back(std::move(rec));
  }

  // Merges the written entries under the folder lock (another bake may have
  // added entries meanwhile), then reports them recorded: a stamp never claims
  // an output the manifest does not list (a process killed in between leaves
  // the stamp old, so ninja runs the edge again and finds the output current).
  void record_written() {
    if (written_.empty()) return;
    {
      DirectoryLock lock(summary_.scene_dir);
      Manifest m = read_manifest(manifest_path());
      m.scene = scene_.name;
      m.preset = scene_.file.string();
      m.tool_version = SKYBAKE_VERSION;
      for (const ManifestEntry& e : written_) m.entries[e.name] = e;
      write_manifest(manifest_path(), m);
    }
    if (options_.on_recorded)
      for (const ManifestEntry& e : written_)
        options_.on_recorded(summary_.scene_dir, e.name, e.input_hash);
  }

  const Scene& scene_;
  const BakeOptions& options_;
  const ProductGraph graph_;
  BakeSummary summary_;
  Manifest before_;
  std::vector<char> stale_, needed_;
  std::vector<std::string> reasons_;
  std::vector<std::optional<Texture>> textures_;
  std::vector<ManifestEntry> written_;
  double bake_seconds_ = 0.0;
};

}  // namespace

BakeSummary bake_scene(const Scene& scene, const BakeOptions& options) {
  return SceneBake(scene, options).run();
}

}  // namespace skybake

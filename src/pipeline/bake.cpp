#include "pipeline/bake.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "core/worker_start.hpp"
#include "io/atomic_file.hpp"
#include "io/bake_log.hpp"
#include "io/file_record.hpp"
#include "io/output_readback.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/freshness.hpp"
#include "pipeline/non_finite_output.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/runtime_metadata.hpp"
#include "pipeline/spectral_bake.hpp"
#include "pipeline/table_conventions.hpp"
#include "pipeline/warnings.hpp"

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
  e.metadata = metadata_to_json(tex.metadata);
  e.input_hash = node.input_hash;
  e.bake_seconds = seconds;
  return e;
}

// One bake of one scene, in stages: decide what is stale, then for each node
// in dependency order report it current, read it back, or compute, write and
// record it (each output enters the manifest as soon as its files are in
// place, so a killed bake keeps what it finished); finally the bake log.
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
    log_ = read_bake_log(log_path());
    mark_stale();
    // Something to compute or read back: TBB's workers start while this
    // thread reads the inputs and sets up the first bake (core/worker_start.hpp).
    if (std::find(needed_.begin(), needed_.end(), 1) != needed_.end()) start_workers();
    std::exception_ptr failure;  // what was recorded before a failure stays recorded
    for (size_t i = 0; i < graph_.nodes.size() && !failure; ++i) try {
        visit(i);
      } catch (...) {
        failure = std::current_exception();
      }
    if (!failure) tidy_manifest();
    record_log();
    if (failure) std::rethrow_exception(failure);
    summary_.seconds = seconds_since(t0);
    return std::move(summary_);
  }

 private:
  fs::path manifest_path() const { return summary_.scene_dir / "manifest.json"; }
  fs::path log_path() const { return summary_.scene_dir / "bake_log.json"; }

  // Checked once per node: a check may hash the node's files.
  const Freshness& freshness(size_t i) {
    if (!freshness_[i]) {
      const FreshnessOptions how{&log_, options_.verify};
      freshness_[i] = check_freshness(graph_.nodes[i], before_, summary_.scene_dir, how);
    }
    return *freshness_[i];
  }

  void create_scene_dir() const {
    create_folder(summary_.scene_dir);
    // Left by killed bakes, beside the outputs and beside the stamps.
    sweep_stale_temporaries(summary_.scene_dir);
    if (fs::is_directory(summary_.scene_dir / ".stamps"))
      sweep_stale_temporaries(summary_.scene_dir / ".stamps");
  }

  // Stale requested nodes, then everything they read (reverse topological order).
  void mark_stale() {
    const size_t n = graph_.nodes.size();
    stale_.assign(n, 0);
    needed_.assign(n, 0);
    reasons_.assign(n, "");
    textures_.resize(n);
    twins_.resize(n);
    freshness_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const GraphNode& node = graph_.nodes[i];
      if (!node.requested) continue;
      const Freshness& f = freshness(i);
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
    if (!scene_.spectral && read_back(i)) {
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
    const ManifestEntry& entry = before_.entries.at(node.spec.name);
    log_current_files(entry);
    note_warnings(entry);
    OutputRecord rec{node.info->name, "up to date", reasons_[i], entry};
    if (options_.on_output) options_.on_output(rec);
    summary_.outputs.push_back(std::move(rec));
  }

  // A dependency the scene writes and that is current on disk is read back
  // (also under --only, where it is not requested in this run); one written
  // in another convention than skybake's is baked again in skybake's layout
  // for its dependents instead.
  bool read_back(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    if (stale_[i] || !scene_.find_output(node.info->name) || !freshness(i).current) return false;
    if (output_convention(node.spec) != TableConvention::skybake) {
      twins_[i] = node.info->bake(scene_, skybake_layout_twin(node.spec), inputs_of(node), {});
      return true;
    }
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
    if (scene_.spectral)  // every needed node at once, group by group (spectral_bake.hpp)
      textures_[i] = take_spectral(i, ctx);
    else
      textures_[i] = node.info->bake(scene_, node.spec, inputs, ctx);
    bake_seconds_ = seconds_since(t_bake);
    Texture& tex = *textures_[i];
    if (node.requested) refuse_non_finite(scene_, node, tex);
    set_meta(tex.metadata, "product", node.info->name);
    set_meta(tex.metadata, "tool", std::string("skybake " SKYBAKE_VERSION));
    set_meta(tex.metadata, "input_hash", node.input_hash);
    set_meta(tex.metadata, "preset", scene_.file.filename().string());
    add_runtime_metadata(scene_, *node.info, tex);
    if (scene_.spectral) add_spectral_metadata(*scene_.spectral, *node.info, tex);
    summary_.computed.push_back(node.info->name);
    // The bakers that read a table read it in skybake's layout.
    if (!scene_.spectral && output_convention(node.spec) != TableConvention::skybake &&
        has_dependents(i))
      twins_[i] = node.info->bake(scene_, skybake_layout_twin(node.spec), inputs, {});
  }

  Texture take_spectral(size_t i, const BakeContext& ctx) {
    if (spectral_.textures.empty()) {
      std::vector<char> measured(graph_.nodes.size(), 0);
      for (size_t k = 0; k < measured.size(); ++k) measured[k] = measures_error(k);
      spectral_ = bake_spectral_graph(scene_, graph_, needed_, measured, ctx, summary_.scene_dir);
    }
    Texture tex = std::move(*spectral_.textures.at(i));
    spectral_.textures[i].reset();
    return tex;
  }

  // Whether output i gets an error record: a stale output of a measured
  // product in skybake's layout.
  bool measures_error(size_t i) const {
    const GraphNode& node = graph_.nodes[i];
    return node.requested && stale_[i] && node.info->measure_error &&
           output_convention(node.spec) == TableConvention::skybake;
  }

  bool has_dependents(size_t i) const {
    for (const GraphNode& other : graph_.nodes)
      if (std::find(other.deps.begin(), other.deps.end(), i) != other.deps.end()) return true;
    return false;
  }

  ProductInputs inputs_of(const GraphNode& node) const {
    ProductInputs inputs;
    for (size_t d : node.deps)
      inputs[graph_.nodes[d].info->name] = twins_[d] ? &*twins_[d] : &*textures_[d];
    return inputs;
  }

  // Writes a computed output's files, measures its error (or tiling) and
  // decides its warnings.
  void write(size_t i) {
    const GraphNode& node = graph_.nodes[i];
    const Texture& tex = *textures_[i];
    // An output's time is computing it and writing its files: block
    // compression can take longer than the bake itself.
    const auto t_write = Clock::now();
    WriteProgress writing;
    if (options_.on_progress)  // the files' own line: encoding shows, not a bar stuck at 100%
      writing = [this, product = node.info->name](const std::string& file, double f) {
        options_.on_progress(product + " writing " + file, f);
      };
    std::vector<ManifestFile> files =
        write_outputs(tex, *node.info, node.spec, summary_.scene_dir, writing);
    const double seconds = bake_seconds_ + seconds_since(t_write);
    OutputRecord rec{node.info->name, "baked", reasons_[i],
                     make_entry(node, tex, std::move(files), seconds)};
    const auto t_measure = Clock::now();
    // Error records are measured on tables in skybake's layout; a spectral
    // table's, group by group as it was baked (spectral_bake.hpp).
    if (measures_error(i))
      rec.entry.error = scene_.spectral
                            ? spectral_.errors.at(i)
                            : node.info->measure_error(scene_, node.spec, inputs_of(node), tex);
    if (node.info->tileable) rec.entry.tiling = tiling_record(tex);
    rec.entry.error_seconds = seconds_since(t_measure);
    for (const OutputWarning& w :
         output_warnings(scene_, node.spec, tex, rec.entry.error, rec.entry.tiling))
      rec.entry.warnings.push_back(w.json());
    note_warnings(rec.entry);
    record(rec.entry);
    if (options_.on_output) options_.on_output(rec);
    summary_.outputs.push_back(std::move(rec));
  }

  // An output's warnings, as the summary lists them: "<output>: <code>: <message>".
  void note_warnings(const ManifestEntry& entry) {
    for (const nlohmann::json& w : entry.warnings)
      summary_.warnings.push_back(entry.name + ": " + warning_line(w));
  }

  // A current output's files were found as recorded: remember their times
  // so the next check need not hash them again.
  void log_current_files(const ManifestEntry& entry) {
    BakeLogEntry& logged = log_.entries[entry.name];
    const BakeLogEntry old = logged;
    for (const ManifestFile& f : entry.files)
      logged.mtime_ns[f.path] = stat_file(summary_.scene_dir / f.path).mtime_ns;
    if (!(old == logged)) log_touched_.insert(entry.name);
  }

  void log_written(const ManifestEntry& entry) {
    BakeLogEntry logged{entry.bake_seconds, entry.error_seconds, {}};
    for (const ManifestFile& f : entry.files)
      logged.mtime_ns[f.path] = stat_file(summary_.scene_dir / f.path).mtime_ns;
    log_.entries[entry.name] = logged;
    log_touched_.insert(entry.name);
  }

  // Merges one written entry into the manifest under the folder lock
  // (another bake may have added entries meanwhile), then reports it
  // recorded: a stamp never claims an output the manifest does not list (a
  // process killed in between leaves the stamp old, so ninja runs the edge
  // again and finds the output current).
  void record(const ManifestEntry& entry) {
    log_written(entry);
    {
      DirectoryLock lock(summary_.scene_dir);
      Manifest m = read_manifest(manifest_path());
      m.entries[entry.name] = entry;
      write_scene_manifest(m);
    }
    if (options_.on_recorded) options_.on_recorded(summary_.scene_dir, entry.name, entry.input_hash);
  }

  // Entries of other outputs are kept: presets of one scene name may share
  // the folder, each recording its own outputs (docs/farm.md, "Concurrent
  // bakes into one folder").
  void write_scene_manifest(Manifest& m) const {
    m.scene = scene_.name;
    m.preset = scene_.file.string();
    m.tool_version = SKYBAKE_VERSION;
    write_manifest(manifest_path(), m);
  }

  // A manifest read with damaged records is rewritten without them even
  // when nothing was baked, so that after any bake its entries for the
  // scene's outputs are what a clean bake writes.
  void tidy_manifest() {
    if (before_.damaged.empty()) return;
    DirectoryLock lock(summary_.scene_dir);
    Manifest m = read_manifest(manifest_path());
    if (m.damaged.empty()) return;  // another bake rewrote it meanwhile
    write_scene_manifest(m);
  }

  // The times of this run's outputs and of the files it found current, merged
  // under the folder lock like the manifest.
  void record_log() {
    if (log_touched_.empty()) return;
    DirectoryLock lock(summary_.scene_dir);
    BakeLog merged = read_bake_log(log_path());
    for (const std::string& name : log_touched_) merged.entries[name] = log_.entries[name];
    write_bake_log(log_path(), merged);
  }

  const Scene& scene_;
  const BakeOptions& options_;
  const ProductGraph graph_;
  BakeSummary summary_;
  Manifest before_;
  std::vector<char> stale_, needed_;
  std::vector<std::string> reasons_;
  std::vector<std::optional<Texture>> textures_;
  SpectralTables spectral_;  // a spectral scene's tables until taken, and their error records
  std::vector<std::optional<Texture>> twins_;  // skybake's layout of an output in another
  std::vector<std::optional<Freshness>> freshness_;
  BakeLog log_;
  std::set<std::string> log_touched_;  // entries this bake changed
  double bake_seconds_ = 0.0;
};

}  // namespace

BakeSummary bake_scene(const Scene& scene, const BakeOptions& options) {
  return SceneBake(scene, options).run();
}

}  // namespace skybake

#include "pipeline/freshness.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/file_record.hpp"
#include "pipeline/output_writer.hpp"

namespace skybake {

namespace {

const ManifestFile* find_file(const ManifestEntry& entry, const std::string& path) {
  for (const ManifestFile& f : entry.files)
    if (f.path == path) return &f;
  return nullptr;
}

// The modification time the bake log recorded for a file, or -1.
int64_t logged_mtime(const FreshnessOptions& options, const ManifestEntry& entry,
                     const std::string& path) {
  if (!options.log) return -1;
  auto e = options.log->entries.find(entry.name);
  if (e == options.log->entries.end()) return -1;
  auto t = e->second.mtime_ns.find(path);
  return t == e->second.mtime_ns.end() ? -1 : t->second;
}

// Empty when the file on disk is the one the manifest recorded, else why not.
std::string file_problem(const ManifestEntry& entry, const std::string& path,
                         const std::filesystem::path& scene_dir, const FreshnessOptions& options) {
  const ManifestFile* record = find_file(entry, path);
  if (!record || record->hash.empty()) return "no size and hash recorded for " + path;
  const FileStat st = stat_file(scene_dir / path);
  if (!st.exists) return "missing file " + path;
  if (!st.regular) return "not a regular file " + path;
  if (st.size != record->size)
    return fmt::format("file {} changed size ({} -> {} bytes)", path, record->size, st.size);
  if (!options.verify && logged_mtime(options, entry, path) == st.mtime_ns) return "";
  try {
    if (hash_file(scene_dir / path) != record->hash) return "file " + path + " changed content";
  } catch (const IoError&) {
    return "unreadable file " + path;
  }
  return "";
}

}  // namespace

Freshness check_freshness(const GraphNode& node, const Manifest& manifest,
                          const std::filesystem::path& scene_dir,
                          const FreshnessOptions& options) {
  auto it = manifest.entries.find(node.spec.name);
  if (it == manifest.entries.end()) return {false, "not baked yet"};
  const ManifestEntry& entry = it->second;
  if (entry.input_hash != node.input_hash)
    return {false, fmt::format("inputs changed (hash {} -> {})", entry.input_hash,
                               node.input_hash)};
  for (const std::string& file : output_files(node.spec)) {
    const std::string problem = file_problem(entry, file, scene_dir, options);
    if (!problem.empty()) return {false, problem};
  }
  return {true, "up to date"};
}

}  // namespace skybake

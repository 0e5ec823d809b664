// out/<scene>/manifest.json: one entry per written output, recording what an
// engine needs to decode it (product, files, formats, dimensions, channels,
// parameterization metadata) and what the incremental cache needs to skip it
// next time (the input hash). Entries are keyed by output name; a bake merges
// its entries into the existing manifest under the folder lock.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace skybake {

struct ManifestFile {
  std::string path;    // relative to the manifest's folder
  std::string format;  // exr, dds, vdb, png
  std::string encoding;  // e.g. "float", "half", "R16G16B16A16_FLOAT"
  uint64_t size = 0;     // bytes, as written
  std::string hash;      // content hash as written (io/file_record.hpp); "" = not recorded
};

struct ManifestEntry {
  std::string product;
  std::string name;
  std::vector<ManifestFile> files;
  std::vector<int> dimensions;  // width, height[, depth]
  int layers = 1;
  std::vector<std::string> channels;
  nlohmann::json metadata = nlohmann::json::object();  // parameterization name and constants...
  std::string input_hash;
  // {rms_rel, max_rel, queries, reference} of a table as an engine reads it
  // (pipeline/error_measures.hpp); null for exact products and pictures.
  nlohmann::json error;
  // {tiles, worst_ratio, tolerance, statistic} of a tileable texture; else null.
  nlohmann::json tiling;
  // [{code, message, ...numbers}] (pipeline/warnings.hpp); empty when none.
  nlohmann::json warnings = nlohmann::json::array();
  // Times vary from run to run: they go to the bake log (io/bake_log.hpp) and
  // to `bake --json`, never into manifest.json.
  double bake_seconds = 0.0;
  double error_seconds = 0.0;
};

struct Manifest {
  std::string scene;
  std::string preset;
  std::string tool_version;
  std::map<std::string, ManifestEntry> entries;  // by output name
  // Why each damaged record was set aside ("/outputs/2/warnings/0/code:
  // expected a string"), or why the whole file was; empty for a manifest as
  // skybake wrote it. A bake that finds any rewrites the manifest.
  std::vector<std::string> damaged;
};

// Missing file -> empty manifest. Not JSON or not an object -> empty manifest
// with one note; an entry of the wrong shape or whose entry hash does not
// match (io/manifest_checks.hpp) -> left out, with one note for the file. It
// is a cache: what is left out is simply baked again. Throws IoError when the
// path is not a regular file (a folder, a FIFO, a device, a link loop), with
// what to remove.
Manifest read_manifest(const std::filesystem::path& file);
void write_manifest(const std::filesystem::path& file, const Manifest& manifest);

nlohmann::json to_json(const ManifestEntry& entry);
ManifestEntry manifest_entry_from_json(const nlohmann::json& j);

}  // namespace skybake

// <scene>/bake_log.json: what differs from run to run and so stays out of
// manifest.json (which is byte-identical for identical inputs): the bake and
// error-measurement times of each output, and each file's modification time
// when it was last written or verified, which lets freshness skip hashing a
// file whose size and time match the record (docs/architecture.md,
// "Freshness"). Like the manifest it is a cache: a missing or malformed log
// costs one content hash per file, never a wrong answer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace skybake {

struct BakeLogEntry {
  double bake_seconds = 0.0;   // wall time of computing the output and writing its files
  double error_seconds = 0.0;  // the error measurement's wall time
  std::map<std::string, int64_t> mtime_ns;  // by file path relative to the scene folder
  bool operator==(const BakeLogEntry& o) const {
    return bake_seconds == o.bake_seconds && error_seconds == o.error_seconds &&
           mtime_ns == o.mtime_ns;
  }
};

struct BakeLog {
  std::map<std::string, BakeLogEntry> entries;  // by output name
};

BakeLog read_bake_log(const std::filesystem::path& file);
void write_bake_log(const std::filesystem::path& file, const BakeLog& log);

}  // namespace skybake

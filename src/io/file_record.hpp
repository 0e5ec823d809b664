// What the manifest records of each written file so that freshness cannot be
// fooled by a truncated or edited output: its size, a content hash, and (in
// the bake log beside the manifest) its modification time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace skybake {

struct FileStat {
  bool exists = false;
  bool regular = false;
  uint64_t size = 0;     // bytes
  int64_t mtime_ns = 0;  // modification time, nanoseconds since the epoch
};

// stat(2) of `path`; exists = false when it cannot be stat'ed.
FileStat stat_file(const std::filesystem::path& path);

// A 64-bit content hash of the file as 16 hex digits, read in large blocks.
// Not cryptographic: it only has to notice a changed file. Throws IoError.
std::string hash_file(const std::filesystem::path& path);

}  // namespace skybake

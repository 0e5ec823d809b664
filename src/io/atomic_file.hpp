// Temporary-name-then-rename output, so a bake killed at any moment leaves no
// partial file under a final name (docs/architecture.md "Files on disk"). The
// temporary lives in the same folder (rename is atomic within one file
// system) and keeps the extension, because OpenImageIO picks the format from
// it:
//   out/earth/transmittance.exr  <-  out/earth/.transmittance.tmp-<pid>.exr
#pragma once

#include <filesystem>
#include <string>

namespace skybake {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();  // removes the temporary unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Where to write.
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& final_path() const { return final_; }
  // Renames the temporary onto the final name; throws IoError on failure.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Writes text atomically (manifests, reports).
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

// True for names skybake uses for temporaries (so cleanup and listings skip them).
bool is_temporary_name(const std::string& filename);

// An exclusive advisory lock (flock) on <dir>/.skybake.lock, held for the
// lifetime of the object: two bakes into one folder serialise their manifest
// updates instead of losing one another's entries.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::filesystem::path& dir);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace skybake

// Temporary-name-then-rename output, so a bake killed at any moment leaves no
// partial file under a final name (docs/architecture.md "Files on disk"). The
// temporary lives in the same folder (rename is atomic within one file
// system), keeps the extension (OpenImageIO picks the format from it) and is
// created with O_EXCL under a name no other process can pick:
//   out/earth/transmittance.exr  <-  out/earth/.transmittance.tmp-<pid>-<ns>-<random>-<host>.exr
// <ns> tells apart processes of one host name that share a pid (PID
// namespaces, a reboot). The name is all a later bake needs to tell a dead
// process's temporary from a live one (sweep_stale_temporaries).
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace skybake {

class AtomicFile {
 public:
  // Creates the temporary (empty, exclusively). Throws IoError naming
  // `final_path` when it cannot.
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();  // removes the temporary unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Where to write: writers open it by path and overwrite it.
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& final_path() const { return final_; }

  // Runs `writer` on the temporary. What it throws is rethrown naming the
  // final path instead of the temporary: an IoError becomes
  // "<final>: cannot write: <reason>".
  void write(const std::function<void(const std::filesystem::path& temp)>& writer);

  // Flushes the temporary to disk (fsync), renames it onto the final name and
  // flushes the folder; throws IoError "<final>: cannot write: <reason>".
  // FolderFlush::by_caller leaves the folder to the caller, who renames
  // several files and then calls flush_folder_of once for all of them.
  enum class FolderFlush { now, by_caller };
  void commit(FolderFlush folder = FolderFlush::now);

  // Renames the temporary onto the final name without any flush.
  void rename_into_place();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  int slot_ = -1;  // in the registry of live temporaries (signal cleanup)
  bool committed_ = false;
};

// Creates `folder` and its parents where missing; throws IoError
// "<folder>: cannot create folder: <reason>". Returns `folder`.
std::filesystem::path create_folder(const std::filesystem::path& folder);

// Flushes the folder holding `final_path`, making the renames into it
// durable; throws IoError "<final>: renamed, but the folder cannot be
// flushed: <reason>".
void flush_folder_of(const std::filesystem::path& final_path);

// How durable write_text_atomic makes a file. `flushed`: the text is on disk
// before the rename and the rename after it (manifests, logs). `renamed`:
// atomic for the process only, no fsync: after a power cut the file may be
// the old one, missing or empty, for files whose loss only costs a redo
// (stamps; docs/architecture.md "Files on disk").
enum class Durability { flushed, renamed };

// Writes text atomically, flushed as `durability` says. Throws IoError
// "<path>: cannot write: <reason>", e.g. "No space left on device".
void write_text_atomic(const std::filesystem::path& path, const std::string& text,
                       Durability durability = Durability::flushed);

// True for names skybake uses for temporaries (so cleanup and listings skip them).
bool is_temporary_name(const std::string& filename);

// Who made a temporary, read back from its name; nullopt for a name this
// version did not make.
struct TemporaryOwner {
  long pid = 0;
  std::string ns;    // 8 hex digits: boot and PID namespace; "00000000" when unknown
  std::string host;  // host name, with characters other than [A-Za-z0-9-] as '_'
};
std::optional<TemporaryOwner> temporary_owner(const std::string& filename);

// The owner fields this process puts into its temporaries' names.
TemporaryOwner this_process_owner();

// Temporaries of another host, another PID namespace or an unreadable owner
// are removed only once untouched for this long (a live writer keeps its
// temporary's modification time fresh, and none takes this long).
constexpr std::chrono::hours kStaleTemporaryAge{24};

// Removes temporaries left in `dir` by processes that are gone: those this
// host's PID namespace shows dead (kill(pid, 0) fails with ESRCH), and any
// temporary untouched for `age`. Best effort: a file that cannot be removed
// is left. Returns how many were removed.
std::size_t sweep_stale_temporaries(const std::filesystem::path& dir,
                                    std::chrono::seconds age = kStaleTemporaryAge);

// SIGINT, SIGTERM and SIGHUP remove this process's live temporaries, then end
// it as the signal would have (the handler restores the default action and
// re-raises). A signal ignored at start stays ignored. Call once, early in main.
void install_temporary_cleanup();

// An exclusive advisory lock (flock) on <dir>/.skybake.lock, held for the
// lifetime of the object: two bakes into one folder serialise their manifest
// updates instead of losing one another's entries. flock belongs to the open
// file description, not the pid, so it holds across PID namespaces; on NFS see
// docs/architecture.md "Files on disk".
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

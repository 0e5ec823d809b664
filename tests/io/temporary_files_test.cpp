// Temporaries no other process can pick, long output names, errors that name
// the output, the sweep of dead processes' temporaries, removal on SIGINT and
// SIGTERM, a full disk and the flushes around the rename.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

// Every name in `dir`, hidden ones included.
std::vector<std::string> all_names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Sets a file's modification time `age` into the past.
void age_file(const fs::path& file, std::chrono::seconds age) {
  timespec times[2];
  ::clock_gettime(CLOCK_REALTIME, &times[0]);
  times[0].tv_sec -= age.count();
  times[1] = times[0];
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0) << file;
}

std::string temp_name(const std::string& stem, long pid, const std::string& ns,
                      const std::string& host, const std::string& ext) {
  return "." + stem + ".tmp-" + std::to_string(pid) + "-" + ns + "-abcd1234-" + host + ext;
}

// A pid that belonged to a process of this namespace that has ended.
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return long(child);
}

TEST(TemporaryFiles, NameCarriesHostNamespaceAndPidAndIsCreatedExclusively) {
  const fs::path dir = test::fresh_dir("temp_names");
  AtomicFile a(dir / "skyview.exr"), b(dir / "skyview.exr");
  EXPECT_NE(a.temp_path(), b.temp_path()) << "a random part, not only the pid";
  EXPECT_TRUE(fs::is_regular_file(a.temp_path())) << "created on construction (O_EXCL)";
  EXPECT_EQ(fs::file_size(a.temp_path()), 0u);
  EXPECT_EQ(a.temp_path().extension(), ".exr");
  const std::optional<TemporaryOwner> owner = temporary_owner(a.temp_path().filename().string());
  ASSERT_TRUE(owner) << a.temp_path();
  const TemporaryOwner me = this_process_owner();
  EXPECT_EQ(owner->pid, long(::getpid()));
  EXPECT_EQ(owner->ns, me.ns);
  EXPECT_EQ(owner->host, me.host);
  EXPECT_NE(me.ns, "00000000") << "boot id and PID namespace are readable here";
  EXPECT_EQ(me.host.find('.'), std::string::npos) << "no dot: the extension stays findable";
}

TEST(TemporaryFiles, OwnerOfANameFromAnotherVersionIsUnknown) {
  EXPECT_FALSE(temporary_owner(".skyview.tmp-1-4.exr"));
  EXPECT_FALSE(temporary_owner("skyview.exr"));
  const std::optional<TemporaryOwner> o =
      temporary_owner(temp_name("a.preview", 42, "0123abcd", "node-7", ".png"));
  ASSERT_TRUE(o);
  EXPECT_EQ(o->pid, 42);
  EXPECT_EQ(o->ns, "0123abcd");
  EXPECT_EQ(o->host, "node-7");
}

TEST(TemporaryFiles, OutputNamesUpTo255BytesAreWritten) {
  const fs::path dir = test::fresh_dir("temp_long");
  for (size_t length : {240u, 250u, 255u}) {
    const std::string name = std::string(length - 4, 'n') + ".exr";
    write_text_atomic(dir / name, "data");
    EXPECT_EQ(test::read_file(dir / name), "data") << length;
    AtomicFile a(dir / name), b(dir / name);
    EXPECT_LE(a.temp_path().filename().string().size(), 255u);
    EXPECT_NE(a.temp_path(), b.temp_path());
    EXPECT_EQ(a.temp_path().extension(), ".exr");
    EXPECT_TRUE(temporary_owner(a.temp_path().filename().string()));
  }
  EXPECT_EQ(all_names(dir).size(), 3u) << "the temporaries went with their objects";
}

TEST(TemporaryFiles, ANameOverNameMaxIsRefusedNamingTheOutput) {
  const fs::path dir = test::fresh_dir("temp_too_long");
  const fs::path final_path = dir / (std::string(252, 'n') + ".exr");
  try {
    AtomicFile f(final_path);
    FAIL() << "a 256-byte name was accepted";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), final_path.string() + ": cannot write: File name too long");
  }
}

TEST(TemporaryFiles, WriterErrorsNameTheOutputNotTheTemporary) {
  const fs::path dir = test::fresh_dir("temp_errors");
  AtomicFile f(dir / "lut.dds");
  const std::string temp = f.temp_path().string();
  try {
    f.write([](const fs::path& tmp) {
      throw IoError(tmp.string() + ": write failed: No space left on device");
    });
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "lut.dds").string() + ": cannot write: write failed: No space left on device");
  }
  try {
    f.write([](const fs::path& tmp) {
      throw Error("cannot open \"" + tmp.string() + "\" (" + tmp.filename().string() + ")");
    });
    FAIL();
  } catch (const IoError&) {
    FAIL() << "an internal error stays internal";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find(".tmp-"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find((dir / "lut.dds").string()), std::string::npos);
  }
}

TEST(TemporaryFiles, RenameFailureNamesTheOutput) {
  const fs::path dir = test::fresh_dir("temp_rename");
  fs::create_directories(dir / "taken" / "inside");  // a non-empty folder under the final name
  AtomicFile f(dir / "taken");
  try {
    f.commit();
    FAIL();
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind((dir / "taken").string() + ": cannot write: ", 0), 0u) << what;
    EXPECT_EQ(what.find(".tmp-"), std::string::npos) << what;
  }
}

TEST(TemporaryFiles, SweepRemovesTemporariesOfDeadProcessesOnly) {
  const fs::path dir = test::fresh_dir("temp_sweep");
  const TemporaryOwner me = this_process_owner();
  const std::string dead = temp_name("a", dead_pid(), me.ns, me.host, ".exr");
  const std::string alive = temp_name("b", long(::getppid()), me.ns, me.host, ".exr");
  const std::string other_ns = temp_name("c", dead_pid(), "00c0ffee", me.host, ".exr");
  const std::string other_host = temp_name("d", 1, me.ns, "elsewhere", ".dds");
  const std::string old_other_host = temp_name("e", 1, me.ns, "elsewhere", ".dds");
  const std::string old_format = ".f.tmp-1-4.exr";
  const std::string old_old_format = ".g.tmp-1-5.exr";
  AtomicFile mine(dir / "h.exr");
  for (const std::string& n : {dead, alive, other_ns, other_host, old_other_host, old_format,
                               old_old_format, std::string("manifest.json"), std::string(".skybake.lock")})
    std::ofstream(dir / n) << "x";
  age_file(dir / old_other_host, kStaleTemporaryAge + std::chrono::hours(1));
  age_file(dir / old_old_format, kStaleTemporaryAge + std::chrono::hours(1));
  age_file(dir / "manifest.json", kStaleTemporaryAge + std::chrono::hours(1));

  EXPECT_EQ(sweep_stale_temporaries(dir), 3u);
  const std::vector<std::string> left = all_names(dir);
  const std::set<std::string> kept(left.begin(), left.end());
  EXPECT_FALSE(kept.count(dead)) << "a dead process of this host and namespace";
  EXPECT_FALSE(kept.count(old_other_host)) << "another host's, past the age";
  EXPECT_FALSE(kept.count(old_old_format)) << "an unknown owner's, past the age";
  for (const std::string& n : {alive, other_ns, other_host, old_format,
                               mine.temp_path().filename().string(), std::string("manifest.json"),
                               std::string(".skybake.lock")})
    EXPECT_TRUE(kept.count(n)) << n;
}

// A child that holds two live temporaries and waits; the signal must remove
// both and end it as the signal does.
void expect_signal_removes_temporaries(int sig) {
  const fs::path dir = test::fresh_dir("temp_signal_" + std::to_string(sig));
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(ready[0]);
    ::signal(sig, SIG_DFL);  // as if started with it at its default (not ignored)
    install_temporary_cleanup();
    AtomicFile a(dir / "a.exr"), b(dir / "b.dds");
    std::ofstream(a.temp_path()) << "partial";
    if (::write(ready[1], "r", 1) != 1) ::_exit(3);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ::close(ready[0]);
  EXPECT_EQ(all_names(dir).size(), 2u);
  ::kill(child, sig);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_TRUE(all_names(dir).empty()) << "left: " << testing::PrintToString(all_names(dir));
}

TEST(TemporaryFiles, SigintRemovesTheProcessTemporaries) { expect_signal_removes_temporaries(SIGINT); }
TEST(TemporaryFiles, SigtermRemovesTheProcessTemporaries) { expect_signal_removes_temporaries(SIGTERM); }

// A tmpfs of `size` mounted on `dir`, unmounted at the end of the test.
class SmallDisk {
 public:
  SmallDisk(const fs::path& dir, const std::string& size) : dir_(dir) {
    const std::string options = "size=" + size;
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
    error_ = mounted_ ? "" : std::strerror(errno);
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }
  const std::string& error() const { return error_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
  std::string error_;
};

TEST(TemporaryFiles, AFullDiskWhileWritingTheManifestSaysSo) {
  const fs::path dir = test::fresh_dir("temp_full_disk");
  SmallDisk disk(dir, "200k");
  ASSERT_TRUE(disk.mounted()) << "mount -t tmpfs (needs root): " << disk.error();
  {
    std::ofstream fill(dir / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 1000 && fill; ++i) fill << block << std::flush;
  }
  try {
    write_text_atomic(dir / "manifest.json", std::string(64 * 1024, '{'));
    FAIL() << "64 KiB written to a full disk";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "manifest.json").string() + ": cannot write: No space left on device");
  }
  EXPECT_EQ(all_names(dir), std::vector<std::string>{"filler"}) << "no temporary, no manifest";
}

// The calls around the renames, as strace sees them (docs/architecture.md
// "Files on disk"): every output file and the manifest are flushed before
// their rename; one folder flush follows the output's renames and comes
// before the manifest's rename, another follows the manifest's and comes
// before the stamp's, which is renamed unflushed.
TEST(TemporaryFiles, FilesAreFlushedBeforeTheirRenameAndTheFolderBeforeTheManifestNamesThem) {
  const fs::path dir = test::fresh_dir("temp_fsync");
  const fs::path trace = dir / "trace.txt";
  const std::string cmd = "strace -f -e trace=openat,fsync,rename,renameat,renameat2 -o '" +
                          trace.string() + "' '" + test::skybake_exe() + "' bake '" +
                          test::source_path("presets/earth.json").string() + "' --only transmittance -q -o '" +
                          (dir / "out").string() + "' -j 1 >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "strace must be installed: " << cmd;
  const fs::path scene = dir / "out" / "earth";
  // The flushes and renames in order: "sync <path>" / "rename <final path>".
  std::vector<std::string> events;
  std::set<std::string> synced;
  std::ifstream in(trace);
  std::map<std::string, std::string> fd_path;   // "<pid> <fd>" -> path
  std::map<std::string, std::string> opening;   // pid -> path of an unfinished openat
  const auto quoted = [](const std::string& line, size_t from = 0) {
    const size_t q = line.find('"', from);
    return q == std::string::npos ? std::string() : line.substr(q + 1, line.find('"', q + 1) - q - 1);
  };
  const auto number_after = [](const std::string& line, size_t at) {
    const size_t end = line.find_first_not_of("0123456789", at);
    return line.substr(at, end == std::string::npos ? std::string::npos : end - at);
  };
  for (std::string line; std::getline(in, line);) {
    const std::string pid = line.substr(0, line.find(' '));
    const size_t eq = line.rfind(") = ");
    const std::string result = eq == std::string::npos ? "" : number_after(line, eq + 4);
    if (line.find("openat(") != std::string::npos) {
      if (line.find("<unfinished") != std::string::npos) opening[pid] = quoted(line);
      else if (!result.empty()) fd_path[pid + " " + result] = quoted(line);
    } else if (line.find("<... openat resumed>") != std::string::npos) {
      if (!result.empty()) fd_path[pid + " " + result] = opening[pid];
    } else if (line.find("fsync(") != std::string::npos) {
      const std::string path = fd_path[pid + " " + number_after(line, line.find("fsync(") + 6)];
      synced.insert(path);
      events.push_back("sync " + path);
    } else if (line.find("rename") != std::string::npos && !quoted(line).empty()) {
      const std::string from = quoted(line);
      const std::string to = quoted(line, line.find(from) + from.size() + 1);
      if (to.find("/.stamps/") == std::string::npos) {
        EXPECT_TRUE(synced.count(from)) << "renamed before its fsync: " << to;
      }
      events.push_back("rename " + to);
    }
  }
  const auto at = [&](const std::string& event) {
    return size_t(std::find(events.begin(), events.end(), event) - events.begin());
  };
  const size_t exr = at("rename " + (scene / "transmittance.exr").string());
  const size_t dds = at("rename " + (scene / "transmittance.dds").string());
  const size_t manifest = at("rename " + (scene / "manifest.json").string());
  const size_t stamp = at("rename " + (scene / ".stamps" / "transmittance.stamp").string());
  ASSERT_LT(std::max(exr, dds), manifest) << "the output's files, then the manifest";
  ASSERT_LT(manifest, stamp) << "the manifest, then the stamp";
  std::ptrdiff_t folder_syncs_before_manifest = 0;
  for (size_t i = std::max(exr, dds); i < manifest; ++i)
    folder_syncs_before_manifest += events[i] == "sync " + scene.string();
  EXPECT_EQ(folder_syncs_before_manifest, 1) << "one folder flush for both files, before the manifest";
  EXPECT_EQ(std::count(events.begin() + std::ptrdiff_t(std::min(exr, dds)),
                       events.begin() + std::ptrdiff_t(std::max(exr, dds)), "sync " + scene.string()),
            0) << "no folder flush between the two files' renames";
  EXPECT_NE(std::find(events.begin() + std::ptrdiff_t(manifest), events.begin() + std::ptrdiff_t(stamp),
                      "sync " + scene.string()),
            events.begin() + std::ptrdiff_t(stamp))
      << "the manifest's rename is flushed before a stamp claims its output";
}

}  // namespace
}  // namespace skybake

// A bake on a flaky farm: killed (SIGKILL) at several moments of writing, interrupted
// (SIGINT, SIGTERM), on a full disk or a read-only folder, and two bakes in
// separate PID namespaces (both PID 1) writing one folder at once. Nothing
// partial ever has a final name, no temporary outlives its process, errors
// name the output, and the next bake repairs everything.
// Runs as root: it mounts tmpfs and uses unshare; where it cannot, it fails.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

extern char** environ;

namespace fs = std::filesystem;
using nlohmann::json;
using skybake::test::fresh_dir;
using skybake::test::list_files;
using skybake::test::read_file;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

// A running process, its output in files.
struct Child {
  pid_t pid = -1;
  fs::path err;
};

Child spawn(const std::vector<std::string>& args, const fs::path& log_dir, const std::string& tag) {
  Child c;
  c.err = log_dir / (tag + ".err");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, c.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  // SIGINT and SIGTERM at their default action even if this process was
  // started with them ignored (a background job of a script).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  if (posix_spawnp(&c.pid, argv[0], &actions, &attr, argv.data(), environ) != 0) c.pid = -1;
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  return c;
}

int wait_status(const Child& c) {
  int status = 0;
  ::waitpid(c.pid, &status, 0);
  return status;
}

std::vector<std::string> bake_args(const fs::path& preset, const fs::path& out,
                                   std::vector<std::string> more = {}) {
  std::vector<std::string> a = {skybake::test::skybake_exe(), "bake", preset.string(), "-o", out.string(), "-q"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

bool is_temporary(const std::string& relative) {
  const std::string name = fs::path(relative).filename().string();
  return name[0] == '.' && name.find(".tmp-") != std::string::npos;
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> t;
  for (const std::string& f : list_files(dir))
    if (is_temporary(f)) t.push_back(f);
  return t;
}

// Polls `condition` until it holds or the child ends; true when it held.
bool poll_until(const Child& c, const std::function<bool()>& condition) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (std::chrono::steady_clock::now() < give_up) {
    if (condition()) return true;
    int status = 0;
    if (::waitpid(c.pid, &status, WNOHANG) == c.pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

// Cloud noise only (no atmosphere): three outputs whose files take long
// enough to write that each moment below is seen while it lasts.
const json kNoiseScene = {
    {"name", "faults"},
    {"outputs",
     {{{"product", "curl"}, {"size", {256, 256}}, {"formats", {"dds", "exr"}}},
      {{"product", "noise_detail"}, {"size", {64, 64, 64}}, {"formats", {"dds", "exr", "vdb"}}},
      {{"product", "noise_shape"}, {"size", {128, 128, 128}}, {"formats", {"dds", "exr", "vdb"}}}}}};

fs::path write_preset(const fs::path& dir, const std::string& name, const json& preset) {
  const fs::path file = dir / name;
  std::ofstream(file) << preset.dump(2);
  return file;
}

// The files of a complete bake, by relative path, bytes (the bake log holds times).
std::map<std::string, std::string> contents(const fs::path& scene_dir) {
  std::map<std::string, std::string> m;
  for (const std::string& f : list_files(scene_dir))
    if (f != "bake_log.json" && f != ".skybake.lock") m[f] = read_file(scene_dir / f);
  return m;
}

class KilledBake : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_dir("faults_reference"));
    preset_ = new fs::path(write_preset(*dir_, "faults.json", kNoiseScene));
    const auto r = run_skybake({"bake", preset_->string(), "-o", (*dir_ / "ref").string(), "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    reference_ = new std::map<std::string, std::string>(contents(*dir_ / "ref" / "faults"));
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete preset_;
    delete reference_;
  }

  // Starts a bake into `out`, kills it with SIGKILL when `moment` holds, and
  // checks what it left: every file under a final name is whole (equal to the
  // reference), the manifest (if any) parses and lists only files as
  // recorded; then a second bake repairs everything and leaves no temporary.
  void kill_when(const fs::path& out, const std::function<bool(const fs::path&)>& moment,
                 std::vector<std::string> more = {}) {
    const fs::path scene = out / "faults";
    const Child c = spawn(bake_args(*preset_, out, more), out.parent_path(), out.filename().string());
    ASSERT_GT(c.pid, 0);
    const bool seen = poll_until(c, [&] { return moment(scene); });
    ::kill(c.pid, SIGKILL);
    const int status = wait_status(c);
    ASSERT_TRUE(seen) << "the bake ended before the moment: " << read_file(c.err);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

    for (const std::string& f : list_files(scene)) {
      if (is_temporary(f) || f == "bake_log.json" || f == ".skybake.lock") continue;
      if (f.rfind(".stamps/", 0) == 0 || f == "manifest.json") continue;
      ASSERT_TRUE(reference_->count(f)) << f;
      EXPECT_TRUE(read_file(scene / f) == reference_->at(f)) << "partial or wrong: " << f;
    }
    if (fs::exists(scene / "manifest.json")) {
      const json manifest = json::parse(read_file(scene / "manifest.json"));
      for (const json& entry : manifest["outputs"])
        for (const json& file : entry["files"]) {
          const std::string path = file["path"];
          ASSERT_TRUE(fs::exists(scene / path)) << "the manifest lists a missing " << path;
          EXPECT_EQ(fs::file_size(scene / path), file["size"].get<uint64_t>()) << path;
          EXPECT_TRUE(read_file(scene / path) == reference_->at(path)) << path;
        }
    }

    const auto repair = run_skybake({"bake", preset_->string(), "-o", out.string(), "-q"});
    ASSERT_EQ(repair.exit_code, 0) << repair.err;
    EXPECT_TRUE(temporaries(scene).empty())
        << "the killed bake's temporaries are swept: " << testing::PrintToString(temporaries(scene));
    EXPECT_TRUE(contents(scene) == *reference_) << "the repaired folder equals a clean bake";
  }

  static fs::path* dir_;
  static fs::path* preset_;
  static std::map<std::string, std::string>* reference_;
};

fs::path* KilledBake::dir_ = nullptr;
fs::path* KilledBake::preset_ = nullptr;
std::map<std::string, std::string>* KilledBake::reference_ = nullptr;

bool has_temporary(const fs::path& scene) { return !temporaries(scene).empty(); }

TEST_F(KilledBake, WhileTheFirstOutputIsWritten) {
  kill_when(fresh_dir("faults_kill_first"), [](const fs::path& scene) {
    return has_temporary(scene) && !fs::exists(scene / "curl.dds");
  });
}

TEST_F(KilledBake, RightAfterTheFirstOutputIsRenamed) {
  kill_when(fresh_dir("faults_kill_renamed"), [](const fs::path& scene) {
    return fs::exists(scene / "curl.dds") && fs::exists(scene / "curl.exr");
  });
}

TEST_F(KilledBake, WhileTheLastOutputIsWritten) {
  kill_when(fresh_dir("faults_kill_last"), [](const fs::path& scene) {
    return fs::exists(scene / "noise_detail.vdb") && has_temporary(scene);
  });
}

// Each output is recorded as soon as its files are in place: a bake killed
// while writing the third output has recorded the first two, and the next
// bake bakes only the third.
TEST_F(KilledBake, KeepsTheOutputsItFinished) {
  const fs::path out = fresh_dir("faults_kill_keeps");
  const fs::path scene = out / "faults";
  const Child c = spawn(bake_args(*preset_, out, {}), out.parent_path(), out.filename().string());
  ASSERT_GT(c.pid, 0);
  const bool seen = poll_until(c, [&] {
    for (const std::string& t : temporaries(scene))
      if (t.find("noise_shape") != std::string::npos) return true;
    return false;
  });
  ::kill(c.pid, SIGKILL);
  wait_status(c);
  ASSERT_TRUE(seen) << "the bake ended before it wrote noise_shape: " << read_file(c.err);
  const json manifest = json::parse(read_file(scene / "manifest.json"));
  std::set<std::string> recorded;
  for (const json& entry : manifest["outputs"]) recorded.insert(entry["name"].get<std::string>());
  EXPECT_EQ(recorded, (std::set<std::string>{"curl", "noise_detail"}));

  const auto next = run_skybake({"bake", preset_->string(), "-o", out.string(), "--json"});
  ASSERT_EQ(next.exit_code, 0) << next.err;
  const json summary = json::parse(next.out);
  EXPECT_EQ(summary["scenes"][0]["computed"], json::array({"noise_shape"}));
  EXPECT_TRUE(contents(scene) == *reference_);
}

TEST_F(KilledBake, OnceTheManifestIsWritten) {
  kill_when(fresh_dir("faults_kill_manifest"),
            [](const fs::path& scene) { return fs::exists(scene / "manifest.json"); });
}

TEST_F(KilledBake, WhileAForcedRebakeReplacesRecordedFiles) {
  const fs::path out = fresh_dir("faults_kill_force");
  ASSERT_EQ(run_skybake({"bake", preset_->string(), "-o", out.string(), "-q"}).exit_code, 0);
  kill_when(
      out, [](const fs::path& scene) { return has_temporary(scene); }, {"--force"});
}

// SIGINT and SIGTERM while an output is written: the process ends by the
// signal and its temporaries are gone.
void expect_signal_leaves_no_temporary(int sig, const std::string& tag) {
  const fs::path out = fresh_dir("faults_signal_" + tag);
  const fs::path preset = write_preset(out.parent_path(), "faults_" + tag + ".json", kNoiseScene);
  const Child c = spawn(bake_args(preset, out), out.parent_path(), "signal_" + tag);
  ASSERT_GT(c.pid, 0);
  const bool seen = poll_until(c, [&] { return has_temporary(out / "faults"); });
  ::kill(c.pid, sig);
  const int status = wait_status(c);
  ASSERT_TRUE(seen) << read_file(c.err);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_TRUE(temporaries(out).empty()) << testing::PrintToString(temporaries(out));
}

TEST(InterruptedBake, SigintLeavesNoTemporary) { expect_signal_leaves_no_temporary(SIGINT, "int"); }
TEST(InterruptedBake, SigtermLeavesNoTemporary) {
  expect_signal_leaves_no_temporary(SIGTERM, "term");
}

// A tmpfs mounted for the test, unmounted at its end.
class Tmpfs {
 public:
  Tmpfs(const fs::path& dir, const std::string& size) : dir_(dir) {
    ok_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
    if (!ok_) error_ = std::strerror(errno);
  }
  ~Tmpfs() {
    if (ok_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool ok() const { return ok_; }
  const std::string& error() const { return error_; }
  bool remount_read_only() {
    return ::mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr) == 0;
  }

 private:
  fs::path dir_;
  bool ok_ = false;
  std::string error_;
};

size_t count_lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

const std::string kEarth = source_path("presets/earth.json").string();

TEST(DiskFaults, AFullDiskIsOneClearErrorWithNoPartialFile) {
  const fs::path out = fresh_dir("faults_full_disk");
  Tmpfs disk(out, "200k");
  ASSERT_TRUE(disk.ok()) << "mount -t tmpfs -o size=200k (needs root): " << disk.error();
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--only", "transmittance"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find((out / "earth" / "transmittance.").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(": cannot write: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(".tmp-"), std::string::npos) << "names the output: " << r.err;
  EXPECT_TRUE(list_files(out).empty()) << testing::PrintToString(list_files(out));
}

TEST(DiskFaults, AReadOnlyFolderIsOneClearErrorAndLeavesTheFilesAsTheyWere) {
  const fs::path out = fresh_dir("faults_read_only");
  Tmpfs disk(out, "16m");
  ASSERT_TRUE(disk.ok()) << "mount -t tmpfs (needs root): " << disk.error();
  ASSERT_EQ(run_skybake({"bake", kEarth, "-o", out.string(), "-q", "--only", "transmittance"})
                .exit_code,
            0);
  const auto before = contents(out / "earth");
  ASSERT_TRUE(disk.remount_read_only()) << std::strerror(errno);
  const auto r = run_skybake({"bake", kEarth, "-o", out.string(), "--force"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find((out / "earth" / "transmittance.exr: cannot write: Read-only file system")
                           .string()),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(contents(out / "earth") == before);
  EXPECT_TRUE(temporaries(out).empty());
}

// Two bakes, each PID 1 of its own PID namespace (as on two farm nodes or in
// two containers), writing the same folder at the same time, round after round.
TEST(SharedFolder, BakesInSeparatePidNamespacesNeitherCollideNorLoseEntries) {
  ASSERT_EQ(std::system("unshare --pid --fork true"), 0)
      << "unshare --pid --fork must work here (root)";
  const fs::path dir = fresh_dir("faults_pid_namespaces");
  json a = {{"name", "shared"},
            {"planet", {{"radius_km", 6360}}},
            {"atmosphere", source_path("presets/atmospheres/earth.json").string()},
            {"outputs",
             {{{"product", "transmittance"}, {"formats", {"exr", "dds"}}},
              {{"product", "skyview"}, {"formats", {"exr", "dds"}}}}}};
  json b = a;
  b["outputs"][1] = {{"product", "aerial_perspective"}, {"formats", {"exr", "dds"}}};
  // One file name in two folders: the outputs record the preset's file name,
  // so the transmittance both write is byte-identical.
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  const fs::path preset_a = write_preset(dir / "a", "shared.json", a);
  const fs::path preset_b = write_preset(dir / "b", "shared.json", b);

  const fs::path ref = dir / "ref";
  ASSERT_EQ(run_skybake({"bake", preset_a.string(), "-o", ref.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run_skybake({"bake", preset_b.string(), "-o", ref.string(), "-q"}).exit_code, 0);
  const json ref_manifest = json::parse(read_file(ref / "shared" / "manifest.json"));

  const fs::path out = dir / "out";
  for (int round = 0; round < 4; ++round) {
    std::vector<Child> bakes;
    for (const fs::path& p : {preset_a, preset_b}) {
      std::vector<std::string> args = {"unshare", "--pid", "--fork"};
      for (const std::string& s : bake_args(p, out, {"--force"})) args.push_back(s);
      bakes.push_back(spawn(args, dir, p.parent_path().filename().string() + std::to_string(round)));
    }
    for (const Child& c : bakes) {
      const int status = wait_status(c);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
          << "round " << round << ": " << read_file(c.err);
    }
    const json manifest = json::parse(read_file(out / "shared" / "manifest.json"));
    EXPECT_EQ(manifest["outputs"], ref_manifest["outputs"]) << "round " << round;
    for (const char* f : {"transmittance.exr", "transmittance.dds", "skyview.exr",
                                 "skyview.dds", "aerial_perspective.exr", "aerial_perspective.dds"})
      EXPECT_TRUE(read_file(out / "shared" / f) == read_file(ref / "shared" / f))
          << "round " << round << ": " << f;
    EXPECT_TRUE(temporaries(out).empty()) << testing::PrintToString(temporaries(out));
  }
}

}  // namespace

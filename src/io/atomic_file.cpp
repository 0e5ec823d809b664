#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/write_all.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

// ---- the registry of live temporaries ---------------------------------------
// Fixed slots the signal handler can walk without allocating or locking: a
// slot's state is free (0), being filled (1) or live (2); only live paths are
// unlinked. A process holds a handful of temporaries at once; past the slots
// a temporary is still written, only not removed on a signal (the next bake
// sweeps it).

constexpr int kSlots = 64;
constexpr int kFree = 0, kFilling = 1, kLive = 2;

struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads slot states");

// A slot holding `path`, not yet live; -1 when none is free.
int reserve_slot(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    return i;
  }
  return -1;
}

void make_live(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kLive);
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree);
}

// The thread that called install_temporary_cleanup: the one that writes.
pthread_t g_main_thread;
std::atomic<bool> g_have_main_thread{false};

extern "C" void remove_temporaries_and_reraise(int sig) {
  const int saved = errno;
  // On another thread the writer could open its temporary again (O_CREAT)
  // after the unlink: the writing thread handles the signal itself, so it
  // writes nothing more.
  if (g_have_main_thread.load() && !pthread_equal(pthread_self(), g_main_thread)) {
    pthread_kill(g_main_thread, sig);
    errno = saved;
    return;
  }
  for (Slot& s : g_slots)
    if (s.state.load() == kLive) ::unlink(s.path);
  ::signal(sig, SIG_DFL);
  errno = saved;
  ::raise(sig);  // pending until the handler returns, then ends the process
}

// ---- names --------------------------------------------------------------------

constexpr const char* kTempMarker = ".tmp-";
constexpr size_t kRandomChars = 8;
constexpr size_t kMaxHostChars = 64;

uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string read_small_file(const char* path) {
  std::ifstream f(path);
  std::string s;
  std::getline(f, s);
  return s;
}

std::string sanitized_host() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0 || buf[0] == '\0') return "unknown";
  std::string host(buf);
  if (host.size() > kMaxHostChars) host.resize(kMaxHostChars);
  for (char& c : host) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-';
    if (!ok) c = '_';
  }
  return host;
}

// The boot and PID namespace of this process: a pid means one process only
// within both. "00000000" when either cannot be read (no /proc).
std::string namespace_tag() {
  const std::string boot = read_small_file("/proc/sys/kernel/random/boot_id");
  char link[256] = {};
  const ssize_t n = ::readlink("/proc/self/ns/pid", link, sizeof link - 1);
  if (boot.empty() || n <= 0) return "00000000";
  const uint64_t h = fnv1a(std::string(link, size_t(n)), fnv1a(boot));
  const std::string tag = fmt::format("{:08x}", uint32_t(h ^ (h >> 32)));
  return tag == "00000000" ? "00000001" : tag;
}

std::string random_part() {
  static std::atomic<uint64_t> counter{0};
  uint64_t bits = 0;
  if (::getrandom(&bits, sizeof bits, GRND_NONBLOCK) != ssize_t(sizeof bits)) {
    timespec ts{};
    ::clock_gettime(CLOCK_REALTIME, &ts);
    bits = fnv1a(fmt::format("{}.{}.{}.{}", ts.tv_sec, ts.tv_nsec, ::getpid(), counter++));
  }
  static const char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s;
  for (size_t i = 0; i < kRandomChars; ++i) {
    s += kAlphabet[bits % 36];
    bits /= 36;
  }
  return s;
}

size_t name_max(const fs::path& dir) {
  const long n = ::pathconf(dir.empty() ? "." : dir.c_str(), _PC_NAME_MAX);
  return n > 0 ? size_t(n) : 255;
}

// Cuts `s` to at most `n` bytes without splitting a UTF-8 sequence.
std::string cut_utf8(const std::string& s, size_t n) {
  if (s.size() <= n) return s;
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  return s.substr(0, n);
}

// ".<stem>.tmp-<pid>-<ns>-<random>-<host><ext>", the stem shortened so the
// name fits the folder's NAME_MAX (the random part keeps it unique).
std::string temporary_name(const fs::path& final_path, const TemporaryOwner& me) {
  const std::string stem = final_path.stem().string();
  const std::string ext = final_path.extension().string();
  const std::string suffix =
      fmt::format("{}{}-{}-{}-{}{}", kTempMarker, me.pid, me.ns, random_part(), me.host, ext);
  const size_t limit = name_max(final_path.parent_path());
  const size_t room = limit > suffix.size() + 1 ? limit - suffix.size() - 1 : 0;
  return "." + cut_utf8(stem, room) + suffix;
}

std::string errno_text(int err) { return std::strerror(err); }

[[noreturn]] void fail_write(const fs::path& final_path, const std::string& reason) {
  throw IoError(fmt::format("{}: cannot write: {}", final_path.string(), reason));
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

// A writer's message about the temporary, told about the final file.
std::string about_final(std::string what, const fs::path& temp, const fs::path& final_path) {
  const std::string prefix = temp.string() + ": ";
  if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
  replace_all(what, temp.string(), final_path.string());
  replace_all(what, temp.filename().string(), final_path.filename().string());
  return what;
}

// fsync of a file or folder by path; 0 or the errno. A folder that cannot be
// flushed on this file system (EINVAL) counts as flushed.
int sync_path(const fs::path& path, bool folder) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (folder ? O_DIRECTORY : 0));
  if (fd < 0) return errno;
  int err = 0;
  while (::fsync(fd) != 0) {
    if (errno == EINTR) continue;
    if (!(folder && errno == EINVAL)) err = errno;
    break;
  }
  ::close(fd);
  return err;
}

}  // namespace

TemporaryOwner this_process_owner() {
  static const std::string ns = namespace_tag();
  static const std::string host = sanitized_host();
  return {long(::getpid()), ns, host};
}

AtomicFile::AtomicFile(fs::path final_path) : final_(std::move(final_path)) {
  const std::string final_name = final_.filename().string();
  if (final_name.size() > name_max(final_.parent_path())) fail_write(final_, errno_text(ENAMETOOLONG));
  const TemporaryOwner me = this_process_owner();
  for (int attempt = 0;; ++attempt) {
    temp_ = final_.parent_path() / temporary_name(final_, me);
    const fs::path absolute = temp_.is_absolute() ? temp_ : fs::absolute(temp_);
    // Live before the file exists, so a signal right after the open finds
    // it. No other process can have made this name: it holds this pid, PID
    // namespace and host.
    slot_ = reserve_slot(absolute.string());
    make_live(slot_);
    const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return;
    }
    const int err = errno;
    unregister_temporary(slot_);
    slot_ = -1;
    if (err != EEXIST || attempt >= 100) fail_write(final_, errno_text(err));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) ::unlink(temp_.c_str());
  unregister_temporary(slot_);  // after the unlink: a signal in between finds it gone
}

void AtomicFile::write(const std::function<void(const fs::path& temp)>& writer) {
  try {
    writer(temp_);
  } catch (const IoError& e) {
    fail_write(final_, about_final(e.what(), temp_, final_));
  } catch (const Error& e) {
    if (e.exit_code() != kExitInternal) throw;
    throw Error(about_final(e.what(), temp_, final_));
  }
}

void AtomicFile::commit(FolderFlush folder) {
  if (const int err = sync_path(temp_, false)) fail_write(final_, errno_text(err));
  rename_into_place();
  if (folder == FolderFlush::now) flush_folder_of(final_);
}

void AtomicFile::rename_into_place() {
  if (::rename(temp_.c_str(), final_.c_str()) != 0) fail_write(final_, errno_text(errno));
  committed_ = true;
  unregister_temporary(slot_);
  slot_ = -1;
}

void flush_folder_of(const fs::path& final_path) {
  const fs::path dir = final_path.parent_path().empty() ? fs::path(".") : final_path.parent_path();
  if (const int err = sync_path(dir, true))
    fail_write(final_path, "renamed, but the folder cannot be flushed: " + errno_text(err));
}

void write_text_atomic(const fs::path& path, const std::string& text, Durability durability) {
  AtomicFile out(path);
  const int fd = ::open(out.temp_path().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail_write(path, errno_text(errno));
  int err = pwrite_all(fd, text.data(), text.size(), 0);
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err) fail_write(path, errno_text(err));
  if (durability == Durability::flushed) out.commit();
  else out.rename_into_place();
}

bool is_temporary_name(const std::string& filename) {
  return !filename.empty() && filename[0] == '.' && filename.find(kTempMarker) != std::string::npos;
}

std::optional<TemporaryOwner> temporary_owner(const std::string& filename) {
  if (!is_temporary_name(filename)) return std::nullopt;
  const size_t at = filename.rfind(kTempMarker);
  const std::string rest = filename.substr(at + std::strlen(kTempMarker));
  // <pid>-<ns>-<random>-<host><ext>
  const size_t a = rest.find('-');
  if (a == std::string::npos || a == 0 || a > 18) return std::nullopt;
  TemporaryOwner owner;
  for (size_t i = 0; i < a; ++i) {
    if (rest[i] < '0' || rest[i] > '9') return std::nullopt;
    owner.pid = owner.pid * 10 + (rest[i] - '0');
  }
  const size_t b = a + 1 + 8;
  if (rest.size() <= b || rest[b] != '-') return std::nullopt;
  owner.ns = rest.substr(a + 1, 8);
  const size_t c = b + 1 + kRandomChars;
  if (rest.size() <= c || rest[c] != '-') return std::nullopt;
  const size_t host_end = rest.find('.', c + 1);
  owner.host = rest.substr(c + 1, host_end == std::string::npos ? std::string::npos
                                                                 : host_end - c - 1);
  if (owner.host.empty()) return std::nullopt;
  return owner;
}

fs::path create_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  return folder;
}

std::size_t sweep_stale_temporaries(const fs::path& dir, std::chrono::seconds age) {
  const TemporaryOwner me = this_process_owner();
  const std::time_t now = std::time(nullptr);
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!is_temporary_name(name)) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    const std::optional<TemporaryOwner> owner = temporary_owner(name);
    const bool here = owner && owner->host == me.host && owner->ns == me.ns && me.ns != "00000000";
    if (here && owner->pid == me.pid) continue;  // this process's own
    bool dead = now - st.st_mtime > std::time_t(age.count());
    if (!dead && here && owner->pid > 0) dead = ::kill(pid_t(owner->pid), 0) != 0 && errno == ESRCH;
    if (dead && ::unlink(it->path().c_str()) == 0) ++removed;
  }
  return removed;
}

void install_temporary_cleanup() {
  g_main_thread = pthread_self();
  g_have_main_thread.store(true);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    ::sigaction(sig, &sa, nullptr);
  }
}

namespace {

// The part of a lock file's message that says how to repair the folder: the
// lock file holds nothing, so anything in its place can simply go.
std::string remove_lock_hint(const fs::path& lock) {
  return fmt::format("; remove {} (skybake creates it again; docs/farm.md, \"Repairing an "
                     "output folder\")",
                     lock.string());
}

}  // namespace

DirectoryLock::DirectoryLock(const fs::path& dir) {
  const fs::path lock = dir / ".skybake.lock";
  // O_NOFOLLOW and O_NONBLOCK: a symbolic link or a FIFO put in its place is
  // refused, never followed or waited on.
  const int flags = O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY;
  fd_ = ::open(lock.c_str(), O_RDWR | flags, 0644);
  // flock needs no write access: an existing lock file in a read-only folder
  // still locks.
  if (fd_ < 0 && (errno == EROFS || errno == EACCES)) fd_ = ::open(lock.c_str(), O_RDONLY | flags);
  if (fd_ < 0) {
    const int err = errno;
    const bool in_the_way = err == EISDIR || err == ELOOP || err == ENXIO;
    throw IoError(fmt::format("{}: cannot open lock file: {}{}", lock.string(),
                              err == ELOOP ? "is a symbolic link" : std::strerror(err),
                              in_the_way ? remove_lock_hint(lock) : ""));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw IoError(fmt::format("{}: cannot open lock file: not a regular file{}", lock.string(),
                              remove_lock_hint(lock)));
  }
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const int err = errno;
    ::close(fd_);
    throw IoError(fmt::format("{}: cannot lock: {}", lock.string(), std::strerror(err)));
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
}

}  // namespace skybake

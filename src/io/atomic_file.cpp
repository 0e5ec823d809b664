#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {
std::atomic<unsigned> g_counter{0};
}

AtomicFile::AtomicFile(fs::path final_path) : final_(std::move(final_path)) {
  const std::string stem = final_.stem().string();
  const std::string ext = final_.extension().string();
  temp_ = final_.parent_path() /
          fmt::format(".{}.tmp-{}-{}{}", stem, ::getpid(), g_counter++, ext);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, final_, ec);
  if (ec) throw IoError(fmt::format("{}: cannot rename from {}: {}", final_.string(),
                                    temp_.string(), ec.message()));
  committed_ = true;
}

void write_text_atomic(const fs::path& path, const std::string& text) {
  AtomicFile out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw IoError(fmt::format("{}: cannot write", path.string()));
  }
  out.commit();
}

bool is_temporary_name(const std::string& filename) {
  return !filename.empty() && filename[0] == '.' && filename.find(".tmp-") != std::string::npos;
}

DirectoryLock::DirectoryLock(const fs::path& dir) {
  const fs::path lock = dir / ".skybake.lock";
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw IoError(fmt::format("{}: cannot open lock file: {}", lock.string(), std::strerror(errno)));
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno != EINTR)
      throw IoError(fmt::format("{}: cannot lock: {}", lock.string(), std::strerror(errno)));
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
}

}  // namespace skybake

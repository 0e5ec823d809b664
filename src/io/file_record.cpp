#include "io/file_record.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/hash.hpp"

namespace skybake {

FileStat stat_file(const std::filesystem::path& path) {
  struct stat st;
  FileStat s;
  if (::stat(path.c_str(), &st) != 0) return s;
  s.exists = true;
  s.regular = S_ISREG(st.st_mode);
  s.size = uint64_t(st.st_size);
  s.mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  return s;
}

std::string hash_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  std::vector<unsigned char> block(1 << 20);  // a multiple of 8: only the last read has a tail
  uint64_t h = 0x243F6A8885A308D3ull, length = 0;
  for (;;) {
    size_t filled = 0;
    while (filled < block.size()) {
      const ssize_t n = ::read(fd, block.data() + filled, block.size() - filled);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int err = errno;
        ::close(fd);
        throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(err)));
      }
      if (n == 0) break;
      filled += size_t(n);
    }
    h = hash_words_mix(h, block.data(), filled);
    length += filled;
    if (filled < block.size()) break;
  }
  ::close(fd);
  return fmt::format("{:016x}", hash_words_finish(h, length));
}

}  // namespace skybake

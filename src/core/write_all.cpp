#include "core/write_all.hpp"

#include <unistd.h>

#include <cerrno>

namespace skybake {

int pwrite_all(int fd, const char* p, std::size_t n, std::uint64_t offset) {
  while (n > 0) {
    const ssize_t written = ::pwrite(fd, p, n, off_t(offset));
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return written < 0 ? errno : EIO;
    p += written;
    n -= std::size_t(written);
    offset += std::uint64_t(written);
  }
  return 0;
}

}  // namespace skybake

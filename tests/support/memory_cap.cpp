#include "support/memory_cap.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <new>

namespace skybake::test {

namespace {

// Bytes this process maps now (/proc/self/statm's first field is in pages).
size_t mapped_bytes() {
  size_t pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  return pages * size_t(::sysconf(_SC_PAGESIZE));
}

}  // namespace

int run_with_memory_headroom(size_t headroom, const std::function<int()>& body) {
  const size_t cap = mapped_bytes() + headroom;
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const rlimit limit{cap, cap};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(97);
    int rc = 0;
    try {
      rc = body();
    } catch (const std::bad_alloc&) {
      rc = 99;
    } catch (...) {
      rc = 98;
    }
    ::_exit(rc);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace skybake::test

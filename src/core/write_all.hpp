// Writing a whole buffer to a file descriptor: the one loop of retries the
// atomic text writer (io/atomic_file.cpp) and the VDB plugin's buffered
// stream (io/buffered_out_file.cpp) share.
#pragma once

#include <cstddef>
#include <cstdint>

namespace skybake {

// Writes all n bytes at `offset` of the open file fd, again after a signal
// or a short write. Returns 0, or the errno of the failure (EIO where a
// write wrote nothing).
int pwrite_all(int fd, const char* p, std::size_t n, std::uint64_t offset);

}  // namespace skybake

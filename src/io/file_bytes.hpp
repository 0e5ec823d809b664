// Reading the start of a binary file we parse ourselves (the DDS and KTX2
// readers): only a regular file, opened without blocking, so a FIFO swapped
// in after the caller's stat cannot hang the reader.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace skybake {

// At most `max_bytes` from the start of the file at `path` (fewer when it is
// shorter). Throws IoError naming the path when it cannot be opened, is not
// a regular file, or a read fails.
std::vector<uint8_t> read_bytes(const std::string& path, uint64_t max_bytes);

}  // namespace skybake

// Test support: Pillow (Debian's python3-pil) as an independent reader of
// image files, through /usr/bin/python3 (a pyenv python has no Pillow).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace skybake::test {

struct PillowImage {
  std::string mode;  // "L", "RGB", "RGBA", ...
  int width = 0, height = 0;
  std::vector<uint8_t> bytes;  // Image.tobytes(): rows from the top, channels interleaved
};

// Opens `path` with Pillow. Throws std::runtime_error with Pillow's message
// when it cannot (a missing interpreter or Pillow fails the caller's test).
PillowImage pillow_read(const std::string& path);

}  // namespace skybake::test

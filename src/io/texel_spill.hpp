// Texels set aside between two uses in an unnamed temporary file, so that a
// long computation in between runs without them resident: a spectral bake
// keeps each output's running sum here while the next wavelength group's
// tables are computed (docs/decisions/spectral-tables.md), as Bruneton's
// GPU bake keeps it in texture memory. The file is opened with O_TMPFILE in
// the folder given (the outputs' own): it has no name, so nothing is left
// behind by a crash; where the file system has no O_TMPFILE, a named file
// is unlinked as soon as it is made. Where no file can be made (or no
// folder is given), the texels stay in memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>

#include "core/texture.hpp"

namespace skybake {

class TexelSpill {
 public:
  explicit TexelSpill(const std::filesystem::path& folder);
  ~TexelSpill();
  TexelSpill(const TexelSpill&) = delete;
  TexelSpill& operator=(const TexelSpill&) = delete;

  // Writes tex's texels under `key` and releases its buffer (its shape and
  // metadata stay); without a file, does nothing.
  void put(size_t key, Texture& tex);
  // Gives back the texels put under `key` (nothing if none are out).
  void take(size_t key, Texture& tex);

 private:
  struct Slot {
    size_t offset = 0, floats = 0;
    bool out = false;
  };
  std::filesystem::path folder_;
  int fd_ = -1;
  size_t end_ = 0;
  std::map<size_t, Slot> slots_;
};

}  // namespace skybake

// Running sums set aside between two uses in an unnamed temporary file, so
// that a long computation in between runs without them resident: a
// spectral bake keeps each output's sum over the wavelength groups here
// while the next group's tables are computed (docs/decisions/
// spectral-tables.md), as Bruneton's GPU bake keeps it in texture memory.
// The file is opened with O_TMPFILE in the folder given (the outputs' own):
// it has no name, so nothing is left behind by a crash; where the file
// system has no O_TMPFILE, a named file is unlinked as soon as it is made.
// Where no file can be made (or no folder is given), the sums stay in
// memory here.
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

  // Keeps tex's texels under `key` and releases tex's buffer (its shape and
  // metadata stay).
  void put(size_t key, Texture& tex);
  // Adds the texels kept under `key` to tex's, value by value in float,
  // and forgets them; read in pieces, so no second buffer of tex's size is
  // made. Nothing kept under `key`: tex is unchanged.
  void add_to(size_t key, Texture& tex);

 private:
  struct Slot {
    size_t offset = 0, floats = 0;
    bool kept = false;
  };
  std::filesystem::path folder_;
  int fd_ = -1;
  size_t end_ = 0;
  std::map<size_t, Slot> slots_;
  std::map<size_t, TexelVector> held_;  // without a file
};

}  // namespace skybake

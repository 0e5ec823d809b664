// The memory a reader may take for what it decodes, checked against the
// sizes a file's header announces before anything is allocated: a 10 KB VDB
// or a 2 MB zip EXR can announce gigabytes. `skybake info` and
// `check-tiling` give their readers --max-memory (default kDefaultReadBudget,
// docs/formats.md "Reading files skybake did not write"); every other reader
// keeps only its format's own limits. Header-only: the VDB plugin checks it
// too.
#pragma once

#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

// What info and check-tiling may decode unless told otherwise: 1 GiB.
constexpr uint64_t kDefaultReadBudget = uint64_t(1) << 30;
// No budget beyond the format's own limits.
constexpr uint64_t kNoReadBudget = UINT64_MAX;

// "1 GiB", "3.9 GiB", "640 MiB": a size for messages.
inline std::string budget_text(uint64_t bytes) {
  if (bytes >= (uint64_t(1) << 30)) return fmt::format("{:.3g} GiB", double(bytes) / (1 << 30));
  return fmt::format("{:.3g} MiB", double(bytes) / (1 << 20));
}

// IoError when reading `path` would take `needed` bytes, more than `budget`;
// `what` says what they hold ("4 channels of 16384x16384 float32 texels").
inline void check_read_budget(const std::string& path, uint64_t needed, uint64_t budget,
                              const std::string& what) {
  if (needed <= budget) return;
  throw IoError(fmt::format("{}: reading it takes {} ({}), more than the memory budget of {}; "
                            "raise --max-memory to read it",
                            path, budget_text(needed), what, budget_text(budget)));
}

}  // namespace skybake

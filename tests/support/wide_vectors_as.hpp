// Turns the AVX2 loops on or off for a test's scope (core/wide_vectors.hpp)
// and restores the switch however the test ends.
#pragma once

#include "core/wide_vectors.hpp"

namespace skybake::test {

struct WideVectorsAs {
  bool before = wide_vectors();
  explicit WideVectorsAs(bool on) { set_wide_vectors(on); }
  ~WideVectorsAs() { set_wide_vectors(before); }
  WideVectorsAs(const WideVectorsAs&) = delete;
  WideVectorsAs& operator=(const WideVectorsAs&) = delete;
};

}  // namespace skybake::test

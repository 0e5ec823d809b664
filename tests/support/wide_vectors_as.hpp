// Turns the AVX2 loops on or off for a test's scope (core/wide_vectors.hpp)
// and restores the switch however the test ends; WidestVectorsAs the AVX-512 ones.
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

// The same for the AVX-512 loops (widest_vectors), AVX2 left as it is.
struct WidestVectorsAs {
  bool before = widest_vectors();
  explicit WidestVectorsAs(bool on) { set_widest_vectors(on); }
  ~WidestVectorsAs() { set_widest_vectors(before); }
  WidestVectorsAs(const WidestVectorsAs&) = delete;
  WidestVectorsAs& operator=(const WidestVectorsAs&) = delete;
};

}  // namespace skybake::test

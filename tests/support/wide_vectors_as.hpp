// Turns the AVX2 loops on or off for a test's scope (core/simd_switches.hpp)
// and restores the switch however the test ends.
#pragma once

#include "core/simd_switches.hpp"

namespace skybake::test {

struct WideVectorsAs {
  bool before = avx2_enabled();
  explicit WideVectorsAs(bool on) { set_avx2_enabled(on); }
  ~WideVectorsAs() { set_avx2_enabled(before); }
  WideVectorsAs(const WideVectorsAs&) = delete;
  WideVectorsAs& operator=(const WideVectorsAs&) = delete;
};

}  // namespace skybake::test

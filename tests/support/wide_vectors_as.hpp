// Turns the AVX2 loops on or off for a test's scope (core/simd_switches.hpp)
// and restores the switch however the test ends; WidestVectorsAs the AVX-512 ones.
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

// The same for the AVX-512 loops (avx512_enabled), AVX2 left as it is.
struct WidestVectorsAs {
  bool before = avx512_enabled();
  explicit WidestVectorsAs(bool on) { set_avx512_enabled(on); }
  ~WidestVectorsAs() { set_avx512_enabled(before); }
  WidestVectorsAs(const WidestVectorsAs&) = delete;
  WidestVectorsAs& operator=(const WidestVectorsAs&) = delete;
};

}  // namespace skybake::test

// The AVX2 switch of the loops written per instruction set. See the header.
#include "core/simd_switches.hpp"

#include <atomic>

namespace skybake {

namespace {

bool cpu_has_avx2() {
#if SKYBAKE_HAS_AVX2
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

std::atomic<bool>& enabled() {
  static std::atomic<bool> on{cpu_has_avx2()};
  return on;
}

}  // namespace

bool avx2_enabled() { return enabled().load(std::memory_order_relaxed); }

void set_avx2_enabled(bool on) {
  enabled().store(on && cpu_has_avx2(), std::memory_order_relaxed);
}

}  // namespace skybake

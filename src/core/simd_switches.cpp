// The AVX2 and AVX-512 switches of the hand-vectorized loops. See the header.
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

bool cpu_has_avx512() {
#if SKYBAKE_HAS_AVX2
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
#else
  return false;
#endif
}

std::atomic<bool>& enabled() {
  static std::atomic<bool> on{cpu_has_avx2()};
  return on;
}

std::atomic<bool>& widest_enabled() {
  static std::atomic<bool> on{cpu_has_avx512()};
  return on;
}

}  // namespace

bool avx2_enabled() { return enabled().load(std::memory_order_relaxed); }

void set_avx2_enabled(bool on) {
  enabled().store(on && cpu_has_avx2(), std::memory_order_relaxed);
}

bool avx512_enabled() { return avx2_enabled() && widest_enabled().load(std::memory_order_relaxed); }

void set_avx512_enabled(bool on) {
  widest_enabled().store(on && cpu_has_avx512(), std::memory_order_relaxed);
}

}  // namespace skybake

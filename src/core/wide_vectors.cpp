// The AVX2 and AVX-512 switches of the hand-vectorized loops. See the header.
#include "core/wide_vectors.hpp"

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

bool wide_vectors() { return enabled().load(std::memory_order_relaxed); }

void set_wide_vectors(bool on) {
  enabled().store(on && cpu_has_avx2(), std::memory_order_relaxed);
}

bool widest_vectors() { return wide_vectors() && widest_enabled().load(std::memory_order_relaxed); }

void set_widest_vectors(bool on) {
  widest_enabled().store(on && cpu_has_avx512(), std::memory_order_relaxed);
}

}  // namespace skybake

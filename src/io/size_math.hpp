// 64-bit size arithmetic for the binary formats we read and write. Sizes
// read from a file are untrusted: products saturate instead of wrapping, so
// no forged header can announce a small total (a saturated total never
// matches a file's size, so nothing is allocated for it).
#pragma once

#include <cstdint>
#include <limits>

namespace skybake::sizes {

constexpr uint64_t kU64Max = std::numeric_limits<uint64_t>::max();

inline uint64_t mul_saturated(uint64_t a, uint64_t b) {
  return a != 0 && b > kU64Max / a ? kU64Max : a * b;
}

inline uint64_t add_saturated(uint64_t a, uint64_t b) {
  return b > kU64Max - a ? kU64Max : a + b;
}

// The first multiple of `a` (> 0) at or after `v`.
inline uint64_t align_up(uint64_t v, uint64_t a) {
  return (v + a - 1) / a * a;
}

}  // namespace skybake::sizes

// The intrinsics of the hand-vectorized loops: SSE2's everywhere it exists,
// AVX2's where its twins are built (core/simd_switches.hpp). For the .cpp
// files that hold such loops only; headers include simd_switches.hpp, whose
// switch is all their users need.
#pragma once

#include <algorithm>
#include <cstddef>

#include "core/simd_switches.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if SKYBAKE_HAS_AVX2
#include <immintrin.h>

namespace skybake {

// std::clamp(v, lo, hi) in each of four lanes, for every non-NaN v, signed
// zeros included: _mm256_max_pd(lo, v) is std::max(v, lo) and
// _mm256_min_pd(hi, v) is std::min(v, hi).
SKYBAKE_AVX2 inline __m256d clamp_lanes(__m256d v, double lo, double hi) {
  return _mm256_min_pd(_mm256_set1_pd(hi), _mm256_max_pd(_mm256_set1_pd(lo), v));
}

// values[first .. first + count) in the lanes of a group of four, count in
// [1, 4]; a short group repeats its last value in the spare lanes. A full
// group is one load: four scalar stores read back as one vector would wait
// for the stores to retire (no store-to-load forwarding across them).
SKYBAKE_AVX2 inline __m256d group_lanes(const double* values, size_t first, int count) {
  if (count == 4) return _mm256_loadu_pd(values + first);
  alignas(32) double lanes[4];
  for (int j = 0; j < 4; ++j) lanes[j] = values[first + size_t(std::min(j, count - 1))];
  return _mm256_load_pd(lanes);
}

}  // namespace skybake
#endif

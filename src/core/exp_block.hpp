// exp of every element of an array, in place (one pointer: no aliasing
// check sends the compiler to its scalar loop), written so that the
// compiler vectorizes it (SSE2: two doubles per instruction, AVX2's twin
// four, no call per value): the transmittance table's quadrature spends most of its time in
// exp (docs/decisions/transmittance-quadrature.md).
//
// Precondition: |x| <= 708 (2^k must be a normal number; a clamp here
// would keep the compiler from vectorizing the loop), callers check it.
//
// exp(x) = 2^k exp(y), k = round(x / ln 2), y = x - k ln 2 with |y| <= ln 2 / 2
// (Cody & Waite reduction: ln 2 split into a head whose product with k is
// exact and a tail), exp(y) by its Taylor polynomial to degree 13, whose
// remainder is below 2e-16 relative on that interval; 2^k is built in the
// exponent bits. Measured within 3e-16 relative of std::exp over
// [-708, 708] (tests/core/exp_block_test.cpp).
//
// expm1_in_place: exp(x) - 1 the same way, with the same precondition
// (beyond it expm1 is -1 or past any use to 1e-307: callers clamp): with the same k and y,
// exp(x) - 1 = 2^k expm1(y) + (2^k - 1) and expm1(y) = y q(y), q the Taylor
// series of (exp(y) - 1) / y to degree 12 (remainder below 2e-17 relative on
// |y| <= ln 2 / 2). k = 0 for |x| <= ln 2 / 2, where the result is y q(y)
// itself and keeps its relative precision at tiny x as std::expm1 does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/simd_switches.hpp"

namespace skybake {

// The Cody & Waite reduction of v (|v| <= 708, see the top): y = v - k ln 2
// and scale = 2^k, shared by exp_one and expm1_one.
struct ExpReduced {
  double y;
  double scale;
};
inline __attribute__((always_inline)) ExpReduced exp_reduce(double v) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kShifter = 0x1.8p52;  // adding it rounds to an integer in the low bits
  constexpr double kLn2Hi = 0x1.62e42fee00000p-1;   // 32 significant bits: k * it is exact
  constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;  // ln 2 - kLn2Hi
  const double t = v * kLog2e + kShifter;
  const double k = t - kShifter;
  const double y = (v - k * kLn2Hi) - k * kLn2Lo;
  // The low bits of t hold k (two's complement); shifted into the
  // exponent field with its bias they are 2^k.
  uint64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  const uint64_t scale_bits = (bits + 1023) << 52;
  double scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return {y, scale};
}

// exp(v) for |v| <= 708, the arithmetic of every element of the loops below.
inline __attribute__((always_inline)) double exp_one(double v) {
  const ExpReduced r = exp_reduce(v);
  const double y = r.y;
  // Estrin's scheme: independent pairs, then powers of y, for a short
  // chain of dependent operations.
  const double y2 = y * y, y4 = y2 * y2;
  const double c01 = 1.0 + y, c23 = 0.5 + y * (1.0 / 6.0);
  const double c45 = 1.0 / 24.0 + y * (1.0 / 120.0), c67 = 1.0 / 720.0 + y * (1.0 / 5040.0);
  const double c89 = 1.0 / 40320.0 + y * (1.0 / 362880.0);
  const double c1011 = 1.0 / 3628800.0 + y * (1.0 / 39916800.0);
  const double c1213 = 1.0 / 479001600.0 + y * (1.0 / 6227020800.0);
  const double c0_3 = c01 + y2 * c23, c4_7 = c45 + y2 * c67, c8_11 = c89 + y2 * c1011;
  const double p = c0_3 + y4 * (c4_7 + y4 * (c8_11 + y4 * c1213));
  return p * r.scale;
}

inline void exp_in_place(double* x, size_t n) {
  for (size_t j = 0; j < n; ++j) x[j] = exp_one(x[j]);
}

#if SKYBAKE_HAS_AVX2
// exp_in_place built for AVX2: the compiler vectorizes the same
// operations four doubles at a time (no FMA, core/simd_switches.hpp), so
// every element has the same bits (tests/core/exp_block_test.cpp).
SKYBAKE_AVX2 inline void exp_in_place_avx2(double* x, size_t n) {
  for (size_t j = 0; j < n; ++j) x[j] = exp_one(x[j]);
}
#endif

// exp_in_place, four doubles at a time where the AVX2 loops run.
inline void exp_block(double* x, size_t n) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) return exp_in_place_avx2(x, n);
#endif
  exp_in_place(x, n);
}

// expm1(v) for |v| <= 708 (see the top).
inline __attribute__((always_inline)) double expm1_one(double v) {
  const ExpReduced r = exp_reduce(v);
  const double y = r.y;
  const double y2 = y * y, y4 = y2 * y2, y8 = y4 * y4;
  const double c01 = 1.0 + y * 0.5, c23 = 1.0 / 6.0 + y * (1.0 / 24.0);
  const double c45 = 1.0 / 120.0 + y * (1.0 / 720.0), c67 = 1.0 / 5040.0 + y * (1.0 / 40320.0);
  const double c89 = 1.0 / 362880.0 + y * (1.0 / 3628800.0);
  const double c1011 = 1.0 / 39916800.0 + y * (1.0 / 479001600.0);
  const double c12 = 1.0 / 6227020800.0;
  const double q = (c01 + y2 * c23) + y4 * (c45 + y2 * c67) + y8 * ((c89 + y2 * c1011) + y4 * c12);
  return r.scale * (y * q) + (r.scale - 1.0);
}

inline void expm1_in_place(double* x, size_t n) {
  for (size_t j = 0; j < n; ++j) x[j] = expm1_one(x[j]);
}

#if SKYBAKE_HAS_AVX2
// expm1_in_place four doubles at a time, the same bits (as exp_in_place_avx2).
SKYBAKE_AVX2 inline void expm1_in_place_avx2(double* x, size_t n) {
  for (size_t j = 0; j < n; ++j) x[j] = expm1_one(x[j]);
}
#endif

// expm1_in_place, four doubles at a time where the AVX2 loops run.
inline void expm1_block(double* x, size_t n) {
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) return expm1_in_place_avx2(x, n);
#endif
  expm1_in_place(x, n);
}

}  // namespace skybake

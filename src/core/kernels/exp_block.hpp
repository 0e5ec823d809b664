// exp of every element of an array, in place, over lanes (Highway; every
// target from one source, kernels/exp_block.cpp, no call per value): the
// transmittance table's quadrature spends most of its time in exp
// (docs/decisions/transmittance-quadrature.md). Each lane does exp_one's
// IEEE operations on the same operands in the same order (no FMA), so every
// target gives exp_one's bits (tests/core/kernels_test.cpp).
//
// Precondition: |x| <= 708 (2^k must be a normal number; a clamp here
// would cost every element a comparison), callers check it.
//
// exp(x) = 2^k exp(y), k = round(x / ln 2), y = x - k ln 2 with |y| <= ln 2 / 2
// (Cody & Waite reduction: ln 2 split into a head whose product with k is
// exact and a tail), exp(y) by its Taylor polynomial to degree 13, whose
// remainder is below 2e-16 relative on that interval; 2^k is built in the
// exponent bits. Measured within 3e-16 relative of std::exp over
// [-708, 708] (tests/core/exp_block_test.cpp).
//
// expm1_block: exp(x) - 1 the same way, with the same precondition
// (beyond it expm1 is -1 or past any use to 1e-307: callers clamp): with the same k and y,
// exp(x) - 1 = 2^k expm1(y) + (2^k - 1) and expm1(y) = y q(y), q the Taylor
// series of (exp(y) - 1) / y to degree 12 (remainder below 2e-17 relative on
// |y| <= ln 2 / 2). k = 0 for |x| <= ln 2 / 2, where the result is y q(y)
// itself and keeps its relative precision at tiny x as std::expm1 does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace skybake {

// The reduction's constants (see the top), shared with the kernel.
constexpr double kExpLog2e = 1.4426950408889634;
constexpr double kExpShifter = 0x1.8p52;  // adding it rounds to an integer in the low bits
constexpr double kExpLn2Hi = 0x1.62e42fee00000p-1;   // 32 significant bits: k * it is exact
constexpr double kExpLn2Lo = 0x1.a39ef35793c76p-33;  // ln 2 - kExpLn2Hi

// The Cody & Waite reduction of v (|v| <= 708, see the top): y = v - k ln 2
// and scale = 2^k, shared by exp_one and expm1_one.
struct ExpReduced {
  double y;
  double scale;
};
inline __attribute__((always_inline)) ExpReduced exp_reduce(double v) {
  const double t = v * kExpLog2e + kExpShifter;
  const double k = t - kExpShifter;
  const double y = (v - k * kExpLn2Hi) - k * kExpLn2Lo;
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

// x[j] = exp_one(x[j]) for j < n.
void exp_block(double* x, size_t n);

// x[j] = expm1_one(x[j]) for j < n.
void expm1_block(double* x, size_t n);

}  // namespace skybake

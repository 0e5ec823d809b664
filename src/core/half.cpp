// Small-float packing (see half.hpp for the formats and the rounding rules).
// The three formats share a 5-bit exponent with bias 15 and differ only in the
// mantissa width, so one encoder and one decoder serve them all.
#include "core/half.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace skybake {
namespace {

constexpr uint32_t kFloatExpMask = 0x7F800000u;  // binary32 Inf pattern
constexpr uint32_t kSmallExpInf = 31;            // exponent field of Inf/NaN

uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Shifts `v` right by `s` (1..31) rounding to nearest, ties to even. A carry
// out of the mantissa lands in the exponent field, which is exactly the IEEE
// behaviour (largest subnormal -> smallest normal, largest finite -> Inf).
uint32_t shift_round_even(uint32_t v, int s) {
  const uint32_t kept = v >> s;
  const uint32_t rest = v & ((1u << s) - 1u);
  const uint32_t tie = 1u << (s - 1);
  return kept + ((rest > tie || (rest == tie && (kept & 1u))) ? 1u : 0u);
}

// Encodes a non-negative finite binary32 (given by its bits, sign cleared)
// into exponent(5, bias 15) + mantissa(`m` bits). Overflow gives Inf.
uint32_t encode_magnitude(uint32_t a, int m) {
  const int e = int(a >> 23) - 127;  // unbiased exponent; -127 for zero/subnormal
  if (e > 15) return kSmallExpInf << m;
  if (e >= -14) {  // normal in the target: re-bias and drop 23 - m mantissa bits
    const uint32_t v = (uint32_t(e + 15) << 23) | (a & 0x7FFFFFu);
    return shift_round_even(v, 23 - m);
  }
  // Subnormal in the target: count units of 2^(-14-m). Anything below half of
  // one unit (e < -15 - m, including binary32 subnormals) rounds to zero.
  if (e < -15 - m) return 0;
  const uint32_t significand = (a & 0x7FFFFFu) | 0x800000u;  // value = sig * 2^(e-23)
  return shift_round_even(significand, 9 - m - e);
}

float decode_magnitude(uint32_t bits, int m) {
  const uint32_t exponent = (bits >> m) & 31u;
  const uint32_t mantissa = bits & ((1u << m) - 1u);
  if (exponent == kSmallExpInf)
    return mantissa ? std::numeric_limits<float>::quiet_NaN()
                    : std::numeric_limits<float>::infinity();
  if (exponent == 0) return std::ldexp(float(mantissa), -14 - m);
  return std::ldexp(float((1u << m) | mantissa), int(exponent) - 15 - m);
}

// Unsigned formats: NaN stays NaN (quiet bit set), +Inf stays Inf, anything
// with the sign bit (negatives, -0, -Inf) becomes 0.
uint32_t encode_unsigned(float value, int m) {
  const uint32_t u = bits_of(value);
  const uint32_t a = u & 0x7FFFFFFFu;
  if (a > kFloatExpMask) return (kSmallExpInf << m) | (1u << (m - 1));
  if (u & 0x80000000u) return 0;
  if (a == kFloatExpMask) return kSmallExpInf << m;
  return encode_magnitude(a, m);
}

}  // namespace

uint16_t half_from_float(float value) {
  const uint32_t u = bits_of(value);
  const uint32_t sign = (u >> 16) & 0x8000u;
  const uint32_t a = u & 0x7FFFFFFFu;
  if (a > kFloatExpMask) return uint16_t(sign | 0x7E00u);  // quiet NaN
  if (a == kFloatExpMask) return uint16_t(sign | 0x7C00u);
  return uint16_t(sign | encode_magnitude(a, 10));
}

float float_from_half(uint16_t bits) {
  const float magnitude = decode_magnitude(bits & 0x7FFFu, 10);
  return (bits & 0x8000u) ? -magnitude : magnitude;
}

uint32_t float11_from_float(float value) {
  return encode_unsigned(value, 6);
}
float float_from_float11(uint32_t bits) {
  return decode_magnitude(bits & 0x7FFu, 6);
}
uint32_t float10_from_float(float value) {
  return encode_unsigned(value, 5);
}
float float_from_float10(uint32_t bits) {
  return decode_magnitude(bits & 0x3FFu, 5);
}

uint32_t r11g11b10_from_rgb(float r, float g, float b) {
  return float11_from_float(r) | (float11_from_float(g) << 11) | (float10_from_float(b) << 22);
}

Rgb rgb_from_r11g11b10(uint32_t bits) {
  return {float_from_float11(bits), float_from_float11(bits >> 11), float_from_float10(bits >> 22)};
}

}  // namespace skybake

// Small-float packing for texture output: IEEE 754 binary16 ("half") and the
// unsigned 11- and 10-bit floats of DXGI_FORMAT_R11G11B10_FLOAT.
//
// Formats (IEEE 754-2008 sec. 3.6 for binary16; the Direct3D 11 functional
// spec, "Floating Point Rules" / "11-bit and 10-bit floats", for the packed
// format; Microsoft's "DXGI_FORMAT" page for the bit order):
//   half:    sign(1) exponent(5, bias 15) mantissa(10)
//   float11: exponent(5, bias 15) mantissa(6), no sign bit
//   float10: exponent(5, bias 15) mantissa(5), no sign bit
//   R11G11B10: R in bits 0..10, G in bits 11..21, B in bits 22..31.
// All three have subnormals (exponent 0), Inf (exponent 31, mantissa 0) and
// NaN (exponent 31, mantissa != 0), like binary16.
//
// Encoding rounds to nearest, ties to even, like IEEE conversion. Finite values
// beyond the largest finite value round to Inf (IEEE overflow); writers that
// must never emit Inf clamp first to the k*Max constants below. The unsigned
// formats map negative values and -Inf to 0 and NaN to a NaN pattern.
// Written here rather than taken from Imath so that skybake_core needs no
// OpenEXR dependency.
#pragma once

#include <cstdint>

namespace skybake {

// Largest finite values: half 2^15 * (2 - 2^-10); float11 2^15 * (2 - 2^-6);
// float10 2^15 * (2 - 2^-5).
constexpr float kHalfMax = 65504.0f;
constexpr float kFloat11Max = 65024.0f;
constexpr float kFloat10Max = 64512.0f;

uint16_t half_from_float(float value);
float float_from_half(uint16_t bits);

// The low 11 (resp. 10) bits of the result hold the encoding.
uint32_t float11_from_float(float value);
float float_from_float11(uint32_t bits);
uint32_t float10_from_float(float value);
float float_from_float10(uint32_t bits);

struct Rgb {
  float r = 0, g = 0, b = 0;
};

uint32_t r11g11b10_from_rgb(float r, float g, float b);
Rgb rgb_from_r11g11b10(uint32_t bits);

}  // namespace skybake

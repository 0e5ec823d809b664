// Order statistics of a baked noise field, used to turn artists' fractions
// ("15% of the map rains", "half the sky is streaked") into thresholds that
// hit them exactly on the baked texels rather than on an assumed noise
// distribution. Deterministic: they depend only on the values, never on the
// order of work or the thread count (std::nth_element selects the same value
// whatever order it visits).
#pragma once

#include <cstddef>

#include "core/texture.hpp"

namespace skybake {

// The k-th largest value (k = 1: the maximum), 1 <= k <= values.size().
float kth_largest(TexelVector values, size_t k);

// Number of texels of a map of n that a fraction in [0, 1] stands for:
// round(fraction * n), clamped to [0, n].
size_t texels_from_fraction(double fraction, size_t n);

// Largest |v| (0 for an empty field).
float max_abs(const TexelVector& values);

// Remaps a field so that `fraction` of its texels are above zero and the
// largest is 1: v' = clamp((v - q) / (max - q), 0, 1) with q the
// (k + 1)-th largest value, k = texels_from_fraction(fraction, n) (q = the
// minimum when k = n: then only the minimum maps to 0). Exactly k texels end
// above 0 when the values are distinct. fraction 0 gives all zeros.
void keep_top_fraction(TexelVector& values, double fraction);

// The octaves of an fBm with `period` cells across `size` texels whose
// finest cells (period * 2^(octaves - 1)) still span at least 2 texels;
// at least 1. Finer octaves would only alias.
int octaves_within_size(int period, int octaves, int size);

}  // namespace skybake

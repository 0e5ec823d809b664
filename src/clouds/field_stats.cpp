#include "clouds/field_stats.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace skybake {

float kth_largest(TexelVector values, size_t k) {
  assert(k >= 1 && k <= values.size());
  const auto nth = values.begin() + std::ptrdiff_t(values.size() - k);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

size_t texels_from_fraction(double fraction, size_t n) {
  const double k = std::round(std::clamp(fraction, 0.0, 1.0) * double(n));
  return std::min(n, size_t(k));
}

float max_abs(const TexelVector& values) {
  float m = 0.0f;
  for (float v : values) m = std::max(m, std::abs(v));
  return m;
}

void keep_top_fraction(TexelVector& values, double fraction) {
  const size_t n = values.size();
  const size_t k = texels_from_fraction(fraction, n);
  if (n == 0) return;
  if (k == 0) {
    std::fill(values.begin(), values.end(), 0.0f);
    return;
  }
  const float top = *std::max_element(values.begin(), values.end());
  const float q =
      k < n ? kth_largest(values, k + 1) : *std::min_element(values.begin(), values.end());
  const double span = double(top) - double(q);
  for (float& v : values)
    v = span > 0.0 ? float(std::clamp((double(v) - q) / span, 0.0, 1.0)) : (v > q ? 1.0f : 0.0f);
}

int octaves_within_size(int period, int octaves, int size) {
  int used = 1;
  while (used < octaves && (long(period) << used) * 2 <= long(size)) ++used;
  return used;
}

}  // namespace skybake

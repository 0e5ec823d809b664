// The geometric tail of a series of scattering orders (docs/decisions/bruneton-stiff-media.md; the derivation is in
// scattering_orders.hpp): in a dense, weakly absorbing sky the orders tend to
// DeltaS_{k+1} = lambda DeltaS_k, lambda the dominant eigenvalue of the
// order-to-order map, one per channel, so the orders after the last one N
// sum to
//   sum_{k > N} DeltaS_k = f DeltaS_N,  f = lambda / (1 - lambda),
// lambda_c = (sum over texels of DeltaS_N) / (sum of DeltaS_{N-1}). Before
// the sequence is geometric the ratio still grows toward lambda, so f is an
// underestimate: the tail never adds light the orders would not have. No
// tail (f = 0) when lambda >= kMaxTailRatio.
// Used by the 4D orders (scattering_orders.cpp) and the azimuth-free 3D
// table (scattering3d_lut.cpp).
#pragma once

#include <string>

#include <fmt/format.h>
#include <glm/glm.hpp>

namespace skybake {

// Order ratios at or above this are not extrapolated (f would exceed 1e4).
constexpr double kMaxTailRatio = 0.9999;

// f per channel from the totals of the last order (N) and the one before it.
inline glm::dvec3 geometric_tail_factor(glm::dvec3 order_sum, glm::dvec3 previous_order_sum) {
  glm::dvec3 f(0.0);
  for (int c = 0; c < 3; ++c) {
    const double ratio = order_sum[c] > 0.0 ? order_sum[c] / previous_order_sum[c] : 0.0;
    f[c] = ratio < kMaxTailRatio ? ratio / (1.0 - ratio) : 0.0;
  }
  return f;
}

// The "geometric_tail" metadata value (double3): f per channel, or 0 when the
// bake has no tail (fixed orders, or the tail turned off): a factor of 0 adds
// nothing, which is what no tail means.
inline glm::dvec3 geometric_tail_metadata(bool tail_mode, glm::dvec3 f) {
  return tail_mode ? f : glm::dvec3(0.0);
}

}  // namespace skybake

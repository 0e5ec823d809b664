// The per-segment terms of one ring's march in the multiple-scattering point
// rule (psi_ms_reference.cpp) that do not depend on the segments before
// it: each channel's weight (1 - exp(-sigma_t dt)) / sigma_t (segment_weights
// from the block's expm1s), and where the segment is lit (the centroid of its
// weight, weight_centroid), that point's radius and its inverse. Five
// divisions and a square root per segment, over lanes (Highway): several
// segments share each, every lane doing ring_segment_term's operations, the
// same bits on every target (tests/verify/kernels_test.cpp).
// The running transmittance and the sums stay in the march, in order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/geometry.hpp"

namespace skybake {

struct RingSegmentTerms {
  std::vector<double> weight[3];  // per channel
  std::vector<double> lit_at;     // distance from the point where the segment is lit
  std::vector<double> lit_radius, inverse_radius;  // max(radius there, Rb), 1 / it
};

// Terms of the n segments [ends[i], ends[i + 1]] of the ray (r, mu), with
// extinction[i] the segment's sigma_t and expm1s[4 i + c] = expm1(-sigma_t[c]
// dt) (c < 3), expm1s[4 i + 3] = expm1(mean sigma_t dt). Segments of zero
// length or extinction get values the march does not read.
void ring_segment_terms(const double* ends, size_t n, const glm::dvec3* extinction,
                        const double* expm1s, double r, double mu, double bottom_m,
                        RingSegmentTerms& out);

// Where in a segment of length dt the light it scatters comes from: the
// centroid of exp(-sigma s) on [0, dt], 1 / sigma - dt / expm1(sigma dt),
// with sigma the channels' mean extinction. dt / 2 in thin air; about
// 1 / sigma from the segment's start where the segment is optically thick,
// so the sun is read where the light scatters, not at a midpoint it never
// reaches (the stiff extreme presets).
inline double weight_centroid(glm::dvec3 extinction, double dt, double expm1_x) {
  const double x = (extinction.x + extinction.y + extinction.z) / 3.0 * dt;
  const double fraction = x < 1e-4 ? 0.5 - x / 12.0 : 1.0 / x - 1.0 / expm1_x;
  return fraction * dt;
}

// The terms of segment i alone (ring_segment_terms' arguments; `out` has
// room for it): the operations every lane of the kernel does.
inline void ring_segment_term(const double* ends, size_t i, const glm::dvec3* extinction,
                              const double* expm1s, double r, double mu, double bottom_m,
                              RingSegmentTerms& out) {
  const double dt = ends[i + 1] - ends[i];
  const glm::dvec3& e = extinction[i];
  const double* em = expm1s + 4 * i;
  for (int c = 0; c < 3; ++c)  // segment_weights_from_expm1
    out.weight[c][i] = e[c] > 0.0 ? -em[c] / e[c] : dt;
  const double lit_at = ends[i] + weight_centroid(e, dt, em[3]);
  const double lit_radius = std::max(radius_after(r, mu, lit_at), bottom_m);
  out.lit_at[i] = lit_at;
  out.lit_radius[i] = lit_radius;
  out.inverse_radius[i] = 1.0 / lit_radius;
}

}  // namespace skybake

// Energy-conserving quadrature along a view ray (docs/reference.md
// "Integrating along a ray"): the
// weights of the in-scattering integrals
//   S = int_0^d T(0, s) sigma_s(s) f(s) ds,   T(0, s) = exp(-int_0^s sigma_t),
// f the light scattered toward the viewer per unit sigma_s (sun times phase
// for single scattering, the phase-averaged radiance for higher orders).
//
// Why not T from the transmittance LUT (a ratio of two bilinear reads) and
// plain Gauss weights: in a dense atmosphere the LUT's texels span orders of
// magnitude of T, the ratio overshoots (clamped at 1) and the quadrature of
// int T sigma_t ds, which must be 1 - T(0, d) <= 1, measured up to 5.5 at
// 1000x Earth Rayleigh: every scattering order then gains energy and the
// series diverges to +inf. Here T is integrated along the ray itself, and on
// every segment [a, b] of ray_segments the weights are scaled so that
//   sum_i weight_i sigma_t(s_i) = T(0, a) (1 - exp(-tau_ab))
// exactly, the segment's S (1 - exp(-sigma d)) / sigma rule: the weights
// sum to at most 1 - T(0, d) whatever the optical depth, so a medium of
// albedo <= 1 never scatters out more than it takes in. On smooth, thin
// media the scale is 1 to the quadrature's accuracy (tests), so nothing is
// lost in accuracy against the Gauss rule.
//
// Inside a segment the optical depth to a node integrates the quadratic
// through the three nodes' sigma_t (exact Lagrange antiderivatives), kept
// monotone; the segment's own depth is the Gauss sum.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"

namespace skybake {

struct TransferNode {
  double s = 0.0;           // distance from the ray's origin, m
  double r = 0.0;           // radius at the node, clamped to the shell, m
  glm::dvec3 weight{0.0};   // quadrature weight times T(0, s), renormalized (above), m
  glm::dvec3 sigma_t{0.0};  // extinction at the node, 1/m
};

struct RayTransfer {
  std::vector<TransferNode> nodes;  // 3 per segment, increasing s
  glm::dvec3 transmittance{1.0};    // T(0, d) = exp(-sum of the segments' depths)
  glm::dvec3 optical_depth{0.0};
};

// The rule for the ray from radius r with zenith cosine mu over [0, d], on
// ray_segments(r, mu, d, nodes). d <= 0 gives no nodes and T = 1.
void ray_transfer(const Atmosphere& atm, double r, double mu, double d, int nodes,
                  RayTransfer& out);

// T(0, d) alone, the same optical depth as ray_transfer.
glm::dvec3 ray_transmittance(const Atmosphere& atm, double r, double mu, double d, int nodes);

}  // namespace skybake

// Psi_ms of Hillaire 2020 eq. 5-10 (the quantity of multiscattering_lut.hpp)
// at one point and one sun, with a quadrature built to converge in few rays:
// the reference of the bake's error record (pipeline/atmosphere_errors.cpp),
// where every query has its own altitude and sun, so no march is shared
// between queries as a table row shares it between its suns.
//
// It integrates the same integral as compute_multiscattering (reading the
// same transmittance table for the sun) with a different quadrature, so the
// record compares the table with a rule it does not share
// (docs/decisions/error-records.md):
// - Zenith cosines: split at the horizon's cosine mu_h(r) as the symmetric
//   Gauss rule is (sphere_rule.hpp), but on each side mu = mu_h -+ c s^2
//   (c the side's width) with Gauss-Legendre nodes in s on [0, 1]. A ray's
//   path length, and so the integrand, has a square-root branch at the
//   horizon (the distance to the ground or through the lowest air goes like
//   sqrt(|mu - mu_h|)); in s it is smooth, where Gauss in mu converges only
//   algebraically.
// - Azimuths: midpoints on the half circle (0, pi), each standing for itself
//   and its mirror image across the plane of the sun and the zenith. The
//   azimuths of one zenith cosine (a ring) cross the same altitudes at the
//   same distances, so the sun-independent march is done once per ring and
//   lit per azimuth.
// - Along a ray: cut at the perigee into pieces of monotone altitude, each
//   piece into segments graded s^2 toward its low end, where the air is
//   densest (as the transmittance quadrature grades, transmittance_lut.cpp),
//   each segment integrated with the medium at its midpoint and the
//   energy-conserving weight of sky_integrator.hpp, the sun read at the
//   centroid of that weight (the midpoint in thin air, near the segment's
//   start where it is optically thick).
// A ring's media and expm1s are taken in blocks (medium_block.hpp,
// core/kernels/exp_block.hpp: within 1e-13 of libm's,
// docs/decisions/error-records.md); its per-segment terms
// (ring_segments.hpp) and the azimuths' sun reads (ring_sun_sums.hpp) several
// segments at a time over lanes, the same bits as one at a time on every
// target.
#pragma once

#include <vector>

#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "core/cached_finite_check.hpp"
#include "core/texture.hpp"

namespace skybake {

struct PointQuadrature {
  int below = 6;     // zenith cosines below the horizon (rays that meet the ground)
  int above = 24;    // zenith cosines above it
  int azimuths = 6;  // per zenith cosine on the half circle (2x on the whole circle)
  int steps = 40;    // segments per ray
};

// A PointQuadrature with its Gauss-Legendre nodes worked out, for many points.
struct PointRule {
  PointQuadrature quadrature;
  std::vector<double> below_nodes, below_weights, above_nodes, above_weights;  // on [-1, 1]
};
PointRule point_rule(const PointQuadrature& quadrature);

// With `finite_table` (null: none), a sample whose scattered light is 0 in
// every channel (the ray's transmittance has underflowed to 0, or the air
// there does not scatter) is left out of the ring's sun reads, and a ring
// stops where its transmittance is 0, once `finite_table` has found the
// transmittance table free of NaN and infinity: each such sample adds 0 times
// a finite sum of reads, so the result has the same bits as without it,
// which reads every sample (tests/verify/psi_ms_reference_test.cpp).
// Eq. 5-10 at radius r (clamped to the shell) for a sun of zenith cosine mu_s
// (clamped); f_ms clamped to kMaxMultiscatteringTransfer as in the table.
// Thread-safe.
MultiscatteringSample multiscattering_at_point(const Atmosphere& atm,
                                               const Texture& transmittance_lut, double r,
                                               double mu_s, const PointRule& rule,
                                               const CachedFiniteCheck* finite_table = nullptr);

}  // namespace skybake

// The sun's transmittance seen from every sample of one ring of the
// multiple-scattering point rule (psi_ms_reference.cpp), summed over the
// ring's four azimuths, where AVX2 runs (core/simd_switches.hpp): four samples
// in the lanes of one group, the radius's half of the read
// (transmittance_at_radius) once per group, then each azimuth's read in the
// same lanes and the sums over azimuths lane by lane, in the one-value loop's
// order (0 + a0 + a1 + a2 + a3); a group wholly in the planet's shadow reads
// nothing (each lane would add the masked read's +0). Per lane the operations of
// transmittance_at_radius and lookup_sun_transmittance on the same operands,
// without FMA: the same bits (tests/verify/ring_sun_sums_test.cpp).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "core/texture.hpp"

namespace skybake {

// sums[i] = sum over j of lookup_sun_transmittance(lut,
// transmittance_at_radius(lut, atm, radii[i]), atm.bottom_radius_m,
// (height + distances[i] cosines[j]) inverse_radii[i]), j = 0..3 in order,
// radii[i] >= atm.bottom_radius_m. Returns false (and writes nothing) where
// the AVX2 loop is not in use.
bool ring_sun_sums(const Texture& lut, const Atmosphere& atm, const double* radii,
                   const double* distances, const double* inverse_radii, size_t n, double height,
                   const double cosines[4], glm::dvec3* sums);

}  // namespace skybake

// The sun's transmittance seen from every sample of one ring of the
// multiple-scattering point rule (multiscattering_point.cpp), summed over the
// ring's four azimuths, the four in the lanes of one AVX2 group
// (core/wide_vectors.hpp). Per lane the operations of lit_ring's one-value
// loop on the same operands (atmosphere/wide_lookups.hpp's reads), summed in
// the same order, so the same bits (tests/atmosphere/wide_vectors_test.cpp).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "atmosphere/transmittance_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

// sums[i] = sum over j of lookup_sun_transmittance(lut, reads[i], bottom_m,
// (height + distances[i] cosines[j]) inverse_radii[i]), j = 0..3 in order.
// Returns false (and writes nothing) where the AVX2 loop is not in use.
bool ring_sun_sums_wide(const Texture& lut, double bottom_m, const TransmittanceAtRadius* reads,
                        const double* distances, const double* inverse_radii, size_t n,
                        double height, const double cosines[4], glm::dvec3* sums);

}  // namespace skybake

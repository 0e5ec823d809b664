// The sun's transmittance seen from every sample of one ring of the
// multiple-scattering point rule (psi_ms_reference.cpp), summed over the
// ring's azimuths: the radius's half of the read (transmittance_at_radius)
// once per sample, then each azimuth's read and the sum over azimuths in
// the one-value loop's order (0 + a0 + a1 + ...), several samples in the
// lanes of one group (atmosphere/kernels/table_lanes-inl.h): the same bits
// as one sample at a time (tests/verify/ring_sun_sums_test.cpp).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "core/texture.hpp"

namespace skybake {

// sums[i] = sum over j of lookup_sun_transmittance(lut,
// transmittance_at_radius(lut, atm, radii[i]), atm.bottom_radius_m,
// (height + distances[i] cosines[j]) inverse_radii[i]), j = 0 .. n_cosines - 1
// in order, for i < n.
void ring_sun_sums(const Texture& lut, const Atmosphere& atm, const double* radii,
                   const double* distances, const double* inverse_radii, size_t n, double height,
                   const double* cosines, size_t n_cosines, glm::dvec3* sums);

}  // namespace skybake

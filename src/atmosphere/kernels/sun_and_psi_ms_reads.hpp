// The two table reads of the sky references' block march (sky_integrator.cpp:
// the sky-view and aerial records' references), a whole ray's points at
// once: the sun's transmittance (lookup_sun_transmittance, Vis of Hillaire
// 2020 eq. 4 included) and Psi_ms (lookup_multiscattering, eq. 11), several
// points in the lanes of one group (table_lanes-inl.h): the same bits as one
// point at a time (tests/atmosphere/sun_and_psi_ms_reads_test.cpp).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

// For k < n: sun[k] = lookup_sun_transmittance(transmittance_lut, atm, r[k],
// mu_s[k]) and, where multiscattering_lut is not null, ms[k] =
// lookup_multiscattering(*multiscattering_lut, mapping, atm, r[k], mu_s[k])
// (ms is not written otherwise). Both tables have three channels.
void read_sun_and_psi_ms(const Atmosphere& atm, const Texture& transmittance_lut,
               const Texture* multiscattering_lut, const MultiscatteringMapping& mapping,
               const double* r, const double* mu_s, size_t n, glm::dvec3* sun, glm::dvec3* ms);

}  // namespace skybake

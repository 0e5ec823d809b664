// The multiple-scattering table's sums over directions (Hillaire 2020 eq.
// 5-8, multiscattering_lut.cpp) for many suns at once, each direction's
// march (direction_march.hpp) lit by every sun.
#pragma once

#include <vector>

#include "atmosphere/direction_march.hpp"

namespace skybake {

// The sum over the rule's directions of w_k L'_k (eq. 5-6 before the
// division by the direction count of an unweighted rule) for suns of zenith
// cosines mu_s[j] (clamped) in the x-z plane, into l2[j], four suns at a time
// where AVX2 runs: the same bits as one sun at a time. Returns how many it
// did: a multiple of four, the rest for the caller.
int sunlit_sums_wide(const Atmosphere& atm, const Texture& transmittance_lut,
                     const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                     const double* mu_s, int n, glm::dvec3* l2);

}  // namespace skybake

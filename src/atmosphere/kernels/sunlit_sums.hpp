// The multiple-scattering table's sums over directions (Hillaire 2020 eq.
// 5-8, multiscattering_lut.cpp) for many suns at once, each direction's
// march (direction_march.hpp) lit by every sun.
#pragma once

#include <vector>

#include "atmosphere/direction_march.hpp"

namespace skybake {

// The sum over the rule's directions of w_k L'_k (eq. 5-6 before the
// division by the direction count of an unweighted rule) for suns of zenith
// cosines mu_s[j] (clamped) in the x-z plane, into l2[j] for j < n, several
// suns in the lanes of one group: the same bits as one sun at a time
// (multiscattering_lut.cpp's sunlit_sum).
void sunlit_sums(const Atmosphere& atm, const Texture& transmittance_lut,
                 const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                 const double* mu_s, int n, glm::dvec3* l2);

}  // namespace skybake

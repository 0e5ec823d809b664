// One direction's march of the multiple-scattering integral (Hillaire 2020
// eq. 5-8) from a point, everything but the sun, and the sum over directions
// under many suns at once (multiscattering_lut.cpp, multiscattering_wide.cpp).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

// The texels of a table row share their point and so their marches, and
// differ in mu_s only.
struct DirectionMarch {
  std::vector<double> distances;                 // of the segment midpoints from the point
  std::vector<glm::dvec3> points;                // segment midpoints
  std::vector<double> radii;                     // |point|, at least Rb
  std::vector<TransmittanceAtRadius> sun_reads;  // the sun's lookups at those radii
  std::vector<glm::dvec3> scattered;  // T sigma_s (1 - exp(-sigma_t dt)) / sigma_t per segment
  glm::dvec3 l_f{0.0};                // L_f of eq. 8: the sum of `scattered`
  double t_exit = 0.0;                // where the ray leaves the atmosphere or meets the ground
  bool ground = false;                // the ray ends on the ground, lit by the sun
  glm::dvec3 ground_up{0.0};          // the ground's normal there
  glm::dvec3 ground_transmittance{1.0};  // T from the point to the ground
};

// The sum over the rule's directions of w_k L'_k (eq. 5-6 before the
// division by the direction count of an unweighted rule) for suns of zenith
// cosines mu_s[j] (clamped) in the x-z plane, into l2[j], four suns at a time
// where AVX2 runs: the same bits as one sun at a time. Returns how many it
// did: a multiple of four, the rest for the caller.
int sunlit_sums_wide(const Atmosphere& atm, const Texture& transmittance_lut,
                     const std::vector<DirectionMarch>& marches, const SphereRule& rule,
                     const double* mu_s, int n, glm::dvec3* l2);

}  // namespace skybake

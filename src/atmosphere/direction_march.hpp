// One direction's march of the multiple-scattering integral (Hillaire 2020
// eq. 5-8) from a point, everything but the sun, and the sum over directions
// under many suns at once (multiscattering_lut.cpp, kernels/sunlit_sums.hpp).
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
}  // namespace skybake

// Rays of the transmittance table's domain, for the tests of the table and
// of the optical depth behind it (tests/atmosphere/transmittance_lut_test.cpp,
// optical_depth_test.cpp). Header only.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "atmosphere/medium.hpp"

namespace skybake::fixtures {

// Cosine of the horizon at radius r: the ray tangent to the ground.
inline double mu_horizon(const Atmosphere& atm, double r) {
  const double x = atm.bottom_radius_m / r;
  return -std::sqrt(std::max(0.0, 1.0 - x * x));
}

struct Ray {
  double r, mu;
};

// Rays of the LUT's domain (they do not hit the ground): radii from the
// ground to the top, cosines from the zenith down to the horizon itself.
inline std::vector<Ray> domain_rays(const Atmosphere& atm) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m, thick = rt - rb;
  std::vector<Ray> rays;
  for (double r :
       {rb, rb + 1e-3 * thick, rb + 0.1 * thick, rb + 0.5 * thick, rt - 1e-4 * thick, rt}) {
    const double mu_h = mu_horizon(atm, r);
    for (double t : {0.0, 1e-6, 1e-3, 0.05, 0.2, 0.5, 0.8, 0.99, 1.0}) {
      const double mu = 1.0 - t * (1.0 - mu_h);  // t = 1 is the horizon
      // At the top every upward ray has d = 0 (transmittance_lut_test.cpp,
      // TransmittanceMapping.TopBoundaryUpwardRaysMapToTheZenithColumn).
      if (r == rt && mu >= 0.0) continue;
      rays.push_back({r, mu});
    }
  }
  return rays;
}

}  // namespace skybake::fixtures

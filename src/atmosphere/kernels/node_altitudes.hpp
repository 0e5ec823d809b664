// The altitudes of the transmittance quadrature's nodes on the table's rule
// (transmittance_lut.cpp), over lanes (Highway): node_altitude_from_perigee
// in every lane, the same bits on every target
// (tests/atmosphere/kernels_test.cpp).
#pragma once

#include <cmath>
#include <cstddef>

namespace skybake {

// The altitude of the node at distance s along a ray whose perigee is
// from_perigee before its origin: sqrt((s + from_perigee)^2 + p2) -
// bottom_radius, p2 = r^2 (1 - mu)(1 + mu) the perigee's radius squared.
// radius_after's arithmetic without its clamps: the root's argument cannot
// be negative, and an altitude a rounding below the ground stays in the
// lowest layer's formula.
inline double node_altitude_from_perigee(double s, double from_perigee, double p2,
                                         double bottom_radius) {
  const double x_p = s + from_perigee;
  return std::sqrt(x_p * x_p + p2) - bottom_radius;
}

// s[j] = node_altitude_from_perigee(s[j], ...) for j < n, in place.
void altitudes_from_perigee(double* s, size_t n, double from_perigee, double p2,
                            double bottom_radius);

}  // namespace skybake

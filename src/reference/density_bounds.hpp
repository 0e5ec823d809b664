// What the reference solvers need to know about a density profile
// (atmosphere/medium.hpp) beyond its value: where it is not smooth, so the
// quadrature can split there, and its maximum and minimum over an altitude
// interval, so the path tracer has bounds of the extinction.
//
// Every layer's formula f(h) = a exp(b h) + c h + d has f'' = a b^2 exp(b h)
// of one sign: f is convex or concave, so it has at most one critical point,
// h* = ln(-c / (a b)) / b, and is monotone on each side of it. The answers
// follow exactly from that: the extremes of clamp(f, 0, 1) over an interval
// are at its ends or at h*; the altitudes where f crosses 0 or 1 (where the clamp
// bends it) are found by bisection on the monotone pieces, to the last bit.
#pragma once

#include <vector>

#include "atmosphere/medium.hpp"

namespace skybake {

// Altitudes (m) strictly inside (0, top_altitude_m) where `profile` is not
// smooth: boundaries between layers and where a layer's formula crosses 0 or
// 1. Sorted, without duplicates.
std::vector<double> profile_kink_altitudes(const DensityProfile& profile, double top_altitude_m);

// The kinks of every component with some extinction, between the ground and
// the top of the atmosphere. Sorted, without duplicates.
std::vector<double> density_kink_altitudes(const Atmosphere& atm);

// An upper bound of density_at(profile, h) for h in [lo_m, hi_m] (lo_m <= hi_m),
// equal to the maximum up to rounding (the supremum, where a layer ends at
// an open boundary). Altitudes below 0 read the first layer, as density_at.
double max_density_over(const DensityProfile& profile, double lo_m, double hi_m);

// A lower bound of density_at(profile, h) for h in [lo_m, hi_m], equal to
// the minimum up to rounding (the infimum at an open layer boundary).
double min_density_over(const DensityProfile& profile, double lo_m, double hi_m);

}  // namespace skybake

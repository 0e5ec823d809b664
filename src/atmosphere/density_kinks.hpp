// Altitudes where a density profile (atmosphere/medium.hpp) is not smooth:
// the boundaries between its layers and the altitudes where a layer's formula
// crosses 0 or 1 and the clamp bends it (the ozone tent at 10 and 40 km).
// Between two of them every layer's formula holds unclamped or clamped
// throughout, which is what the transmittance's quadrature and its closed
// form for linear layers cut rays at (docs/reference.md "Transmittance").
#pragma once

#include <vector>

#include "atmosphere/medium.hpp"

namespace skybake {

// Appends the kink altitudes of `profile` strictly inside (0, top_h).
// Crossings are solved for the pure-linear and pure-exponential layers, the
// only shapes the profile helpers build.
void add_profile_kinks(const DensityProfile& profile, double top_h, std::vector<double>& out);

// True when no layer of `profile` has an exponential term: the density is
// then piecewise c h + d in the altitude, clamped to [0, 1].
bool is_piecewise_linear(const DensityProfile& profile);

}  // namespace skybake

#include "atmosphere/medium.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

double density_at(const DensityProfile& profile, double h) {
  if (profile.layers.empty()) return 0.0;
  const DensityLayer& l = layer_at(profile, h);
  return layer_density(l, h, l.exp_term == 0.0 ? 0.0 : std::exp(l.exp_scale_per_m * h));
}

DensityProfile exponential_profile(double scale_height_m) {
  DensityLayer l;
  l.exp_term = 1.0;
  l.exp_scale_per_m = -1.0 / scale_height_m;
  return {{l}};
}

DensityProfile tent_profile(double bottom_m, double center_m, double top_m) {
  // Rising: (h - bottom) / (center - bottom); falling: (top - h) / (top - center).
  DensityLayer below;
  below.width_m = center_m;
  below.linear_term_per_m = 1.0 / (center_m - bottom_m);
  below.constant_term = -bottom_m / (center_m - bottom_m);
  DensityLayer above;
  above.linear_term_per_m = -1.0 / (top_m - center_m);
  above.constant_term = top_m / (top_m - center_m);
  return {{below, above}};
}

DensityProfile uniform_profile(double bottom_m, double top_m) {
  DensityLayer empty;  // [0, bottom)
  empty.width_m = bottom_m;
  DensityLayer slab;  // [bottom, top)
  slab.width_m = top_m - bottom_m;
  slab.constant_term = 1.0;
  DensityLayer above;  // density 0 above
  if (bottom_m <= 0.0) return {{slab, above}};
  return {{empty, slab, above}};
}

MediumSample sample_medium(const Atmosphere& atm, double h) {
  MediumSample s;
  for (const MediumComponent& c : atm.components) {
    const double d = density_at(c.density, h);
    if (d == 0.0) continue;
    s.scattering += d * c.scattering_per_m;
    s.extinction += d * (c.scattering_per_m + c.absorption_per_m);
  }
  return s;
}

glm::dvec3 extinction_at(const Atmosphere& atm, double h) {
  return sample_medium(atm, h).extinction;
}

}  // namespace skybake

// The 4D table's shape for Mie-shaped multiple scattering; see the header.
#include "atmosphere/orders_resolution.hpp"

#include <algorithm>

#include "atmosphere/scattering_lut.hpp"

namespace skybake {

GroupScatteringDepths vertical_scattering_depths(const Atmosphere& atm) {
  // Midpoint rule on a grid fine against every scale height the presets
  // use (4000 steps: 25 m on Earth's 100 km; (dh / H)^2 / 24, 2e-5 for a
  // 1.2 km scale height, far below what the rule compares).
  constexpr int kSteps = 4000;
  const double top = atm.top_radius_m - atm.bottom_radius_m, dh = top / kSteps;
  GroupScatteringDepths d;
  for (int i = 0; i < kSteps; ++i) {
    glm::dvec3 rayleigh, mie;
    scattering_by_group(atm, (i + 0.5) * dh, rayleigh, mie);
    d.rayleigh += rayleigh * dh;
    d.mie += mie * dh;
  }
  return d;
}

bool mie_shapes_multiple_scattering(const Atmosphere& atm) {
  const GroupScatteringDepths d = vertical_scattering_depths(atm);
  return d.mie.x > d.rayleigh.x || d.mie.y > d.rayleigh.y || d.mie.z > d.rayleigh.z;
}

BrunetonSpec sky_light_field_shape(const Atmosphere& atm, BrunetonSpec spec) {
  if (!mie_shapes_multiple_scattering(atm)) return spec;
  spec.mu_size = std::max(spec.mu_size, kSkyLightMieMu);
  spec.nu_size = std::max(spec.nu_size, kSkyLightMieNu);
  return spec;
}

BrunetonSpec with_mie_lobe_shape(BrunetonSpec spec) {
  spec.r_size = kMieLobeShape[0];
  spec.mu_size = kMieLobeShape[1];
  spec.mu_s_size = kMieLobeShape[2];
  spec.nu_size = kMieLobeShape[3];
  return spec;
}

}  // namespace skybake

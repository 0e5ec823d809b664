// Energy balance of a baked 4D table. See the header.
#include "atmosphere/energy_balance.hpp"

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/math.hpp"

namespace skybake {

glm::dvec3 sun_zenith_out_over_in(const Atmosphere& atm, const BrunetonTextures& t,
                                  bool irradiance_includes_direct, int cosines) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  glm::dvec3 up(0.0);
  for (int i = 0; i < cosines; ++i) {
    const double mu = -(i + 0.5) / cosines;
    const bool ground = ray_intersects_ground(rb, rt, mu);
    up += (2.0 * kPi * -mu / cosines) *
          lookup_scattering(t.scattering, t.single_mie, t.shape, atm, rt, mu, 1.0, mu, ground);
  }
  glm::dvec3 ground = lookup_irradiance(t.irradiance, atm, rb, 1.0);
  if (!irradiance_includes_direct) ground += lookup_irradiance(t.direct_irradiance, atm, rb, 1.0);
  const glm::dvec3 out = up + (glm::dvec3(1.0) - atm.ground_albedo) * ground;
  glm::dvec3 ratio(0.0);
  for (int c = 0; c < 3; ++c)
    if (atm.sun_illuminance[c] > 0.0) ratio[c] = out[c] / atm.sun_illuminance[c];
  return ratio;
}

}  // namespace skybake

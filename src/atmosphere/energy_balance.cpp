// Energy balance of a baked 4D or 3D table. See the header.
#include "atmosphere/energy_balance.hpp"

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// int over cos(theta) in (0, 1] of L(cos) cos 2 pi, midpoint rule; `down`
// reads the rays below the horizontal (cosine -c), else above it (c).
template <typename Radiance>
glm::dvec3 hemisphere_flux(const Radiance& radiance, int cosines, bool down) {
  glm::dvec3 sum(0.0);
  for (int i = 0; i < cosines; ++i) {
    const double c = (i + 0.5) / cosines;
    sum += (2.0 * kPi * c / cosines) * radiance(down ? -c : c);
  }
  return sum;
}

// (up through the top + (1 - albedo) ground) / E_sun per channel.
glm::dvec3 out_over_in(const Atmosphere& atm, const glm::dvec3& up, const glm::dvec3& ground) {
  const glm::dvec3 out = up + (glm::dvec3(1.0) - atm.ground_albedo) * ground;
  glm::dvec3 ratio(0.0);
  for (int c = 0; c < 3; ++c)
    if (atm.sun_illuminance[c] > 0.0) ratio[c] = out[c] / atm.sun_illuminance[c];
  return ratio;
}

}  // namespace

glm::dvec3 sun_zenith_out_over_in(const Atmosphere& atm, const BrunetonTextures& t,
                                  bool irradiance_includes_direct, int cosines) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const glm::dvec3 up = hemisphere_flux(
      [&](double mu) {
        return lookup_scattering(t.scattering, t.single_mie, t.shape, atm, rt, mu, 1.0, mu,
                                 ray_intersects_ground(rb, rt, mu));
      },
      cosines, true);
  glm::dvec3 ground = lookup_irradiance(t.irradiance, atm, rb, 1.0);
  if (!irradiance_includes_direct) ground += lookup_irradiance(t.direct_irradiance, atm, rb, 1.0);
  return out_over_in(atm, up, ground);
}

glm::dvec3 sun_zenith_out_over_in_3d(const Atmosphere& atm, const Scattering3dTextures& t,
                                     const Texture& transmittance_lut, int cosines) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m, h_top = rt - rb;
  auto at = [&](double h, double mu) {
    const double r = rb + h;
    return lookup_scattering3d(t.scattering, t.mie, t.shape, atm, h, mu, 1.0, mu,
                               ray_intersects_ground(rb, r, mu));
  };
  const glm::dvec3 up = hemisphere_flux([&](double mu) { return at(h_top, mu); }, cosines, true);
  const glm::dvec3 sky = hemisphere_flux([&](double mu) { return at(0.0, mu); }, cosines, false);
  const glm::dvec3 ground = sky + compute_direct_irradiance(atm, transmittance_lut, rb, 1.0);
  return out_over_in(atm, up, ground);
}

}  // namespace skybake

// One view ray marched once and read for many suns (the sky-light tables'
// sun columns and the ground's sky table share their rays).
//
// The march is integrate_scattered_luminance's (sky_integrator.hpp) with
// uniform segments and the medium at their midpoints, eq. 1-4 and 11 of
// Hillaire 2020:
//   L(sun) = E sum_i T_i w_i (T_sun,i(sun) sum_k sigma_s,k,i p_k(nu)
//                              + Psi_i(sun) sigma_s,i)
// with T_i the transmittance from the viewer to segment i and w_i its
// closed-form weight. Everything but T_sun, Psi and the phases is the
// same for every sun, so it is worked out once per ray: the segments'
// media, T_i w_i sigma_s,k,i, and the radius parts of the two table reads.
// A sun then costs its reads and a sum per segment. Same terms as the
// per-ray march, summed in another order: equal to rounding
// (tests/atmosphere/sky_ray_suns_test.cpp).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

class SunSharedRay {
 public:
  // A ray from `position` (planet-centred, inside the atmosphere or on its
  // ground) along the unit `dir`, `steps` segments to where it leaves the
  // atmosphere or meets the ground. multiscattering_lut may be null (single
  // scattering only); `mapping` is its mapping, parsed by the caller.
  SunSharedRay(const Atmosphere& atm, const Texture& transmittance_lut,
               const Texture* multiscattering_lut, const MultiscatteringMapping* mapping,
               glm::dvec3 position, glm::dvec3 dir, int steps);

  // In-scattered luminance for the unit sun direction, units of E; with a
  // multiple-scattering table, eq. 11's term from it too.
  glm::dvec3 scattered(glm::dvec3 sun_dir) const;

  // The ground's diffuse response to the sun where the ray meets it (eq. 1
  // L_o: albedo / pi E T_sun mu_s), seen through the ray; 0 elsewhere.
  glm::dvec3 sunlit_ground(glm::dvec3 sun_dir) const;

  bool meets_ground() const { return meets_ground_; }
  glm::dvec3 ground_up() const { return ground_up_; }        // unit, where it meets it
  glm::dvec3 transmittance() const { return transmittance_; }  // viewer to the ray's end

 private:
  struct Segment {
    glm::dvec3 up;    // unit position of the midpoint (mu_s = up . sun)
    double mu_v;      // the ray's zenith cosine there
    TransmittanceAtRadius sun_read;
    MultiscatteringAtRadius psi_read;
    glm::dvec3 ms;    // E T_i w_i sigma_s,i
  };
  const Atmosphere& atm_;
  const Texture& tlut_;
  const Texture* mslut_;
  MultiscatteringMapping mapping_{};
  glm::dvec3 dir_;
  std::vector<const MediumComponent*> media_;  // present ones, in the atmosphere's order
  std::vector<Segment> segments_;
  std::vector<glm::dvec3> single_;  // [segment][component]: E T_i w_i sigma_s,k,i
  bool meets_ground_ = false;
  glm::dvec3 ground_up_{0.0};
  glm::dvec3 transmittance_{1.0};
};

}  // namespace skybake

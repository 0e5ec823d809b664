// Phase functions of the atmosphere's media (docs/reference.md "Atmosphere model"),
// as pure functions of the scattering cosine. Each is a probability density
// over the sphere of directions: it integrates to 1 over 4 pi sr (tested).
//
// Cosine convention (get the sign right, or the Mie halo ends up opposite the
// sun): cos_theta is the cosine of the scattering angle, between the incident
// light's travel direction and the scattered light's travel direction. For a
// view ray marched from the camera with direction v and a sun in direction s
// (pointing toward the sun), the light travels along -s and, scattered toward
// the camera, along -v, so cos_theta = dot(-s, -v) = dot(v, s): Bruneton's and
// Hillaire's nu. cos_theta = 1 is forward scattering (looking at the sun), and
// Mie phases with g > 0 peak there.
#pragma once

#include "atmosphere/medium.hpp"
#include "core/math.hpp"

namespace skybake {

// 1 / (4 pi): scatters equally in every direction (multiple-scattering LUT).
inline double isotropic_phase() {
  return 1.0 / (4.0 * kPi);
}

// Rayleigh: 3 (1 + c^2) / (16 pi).
inline double rayleigh_phase(double cos_theta) {
  const double c = clamp_cosine(cos_theta);
  return 3.0 * (1.0 + c * c) / (16.0 * kPi);
}

// Cornette-Shanks (Mie; Bruneton 2017 MiePhaseFunction), g in (-1, 1):
//   3/(8 pi) (1 - g^2)(1 + c^2) / ((2 + g^2)(1 + g^2 - 2 g c)^1.5).
// Rayleigh's 3 (1 + c^2) / (16 pi) at g = 0.
inline double cornette_shanks_phase(double cos_theta, double g) {
  const double c = clamp_cosine(cos_theta);
  const double k = 3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g);
  const double w = 1.0 + g * g - 2.0 * g * c;
  return k * (1.0 + c * c) / (w * std::sqrt(w));
}

// Henyey-Greenstein, g in (-1, 1): (1 - g^2) / (4 pi (1 + g^2 - 2 g c)^1.5).
inline double henyey_greenstein_phase(double cos_theta, double g) {
  const double c = clamp_cosine(cos_theta);
  const double w = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * kPi * w * std::sqrt(w));
}

// The phase of a medium component (MediumComponent::phase, ::g); 0 for a
// component that only absorbs.
inline double phase_function(PhaseKind kind, double g, double cos_theta) {
  switch (kind) {
    case PhaseKind::rayleigh:
      return rayleigh_phase(cos_theta);
    case PhaseKind::cornette_shanks:
      return cornette_shanks_phase(cos_theta, g);
    case PhaseKind::henyey_greenstein:
      return henyey_greenstein_phase(cos_theta, g);
    case PhaseKind::none:
      break;
  }
  return 0.0;
}

}  // namespace skybake

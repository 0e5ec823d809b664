// Sampling the phase functions of phase.hpp, each sampler beside its
// density and the inverse of its cumulative distribution (tests round-trip
// them and check the sampled moments against quadrature of the density).
//
// All samplers return c, the cosine of the scattering angle, between the
// direction light travels before and after the event (phase.hpp's
// convention: c = 1 is forward). The density of c on [-1, 1] is
// 2 pi p(c) (the phase integrated over the azimuth).
//   Rayleigh: 3/8 (1 + c^2); CDF (c^3 + 3 c + 4) / 8, inverted by Cardano.
//   Henyey-Greenstein: (1 - g^2) / (2 (1 + g^2 - 2 g c)^1.5); CDF and its
//     inverse in closed form (the classic formula).
//   Cornette-Shanks: HG samples of the same g accepted with probability
//     (1 + c^2) / 2 (p_CS / p_HG = 3 (1 + c^2) / (2 (2 + g^2)) is at most
//     3 / (2 + g^2), so the accepted samples follow p_CS exactly; at least
//     half are accepted).
// A path tracer tracing backward from the eye along w samples the next
// direction w' with dot(w', w) = c: light then travels along -w' and leaves
// along -w, and dot(-w', -w) = c.
#pragma once

#include <cassert>
#include <cmath>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "core/math.hpp"

namespace skybake {

// ---- Rayleigh ---------------------------------------------------------------

inline double rayleigh_cosine_pdf(double c) {
  return 0.375 * (1.0 + c * c);
}
inline double rayleigh_cosine_cdf(double c) {
  c = clamp_cosine(c);
  return (c * c * c + 3.0 * c + 4.0) / 8.0;
}
// Solves c^3 + 3c = q with q = 8u - 4: c = A - 1/A, A^3 = q/2 + sqrt(q^2/4 + 1)
// (written without cancellation for q < 0).
inline double rayleigh_cosine_from_cdf(double u) {
  const double q = 8.0 * u - 4.0;
  const double root = std::sqrt(0.25 * q * q + 1.0);
  const double y = q >= 0.0 ? 0.5 * q + root : 1.0 / (root - 0.5 * q);
  const double a = std::cbrt(y);
  return clamp_cosine(a - 1.0 / a);
}

// ---- Henyey-Greenstein ------------------------------------------------------
//
// Written without dividing by g (exact at g = 0, no isotropic special case)
// and without cancellation at the forward peak, where g = 0.999 puts a
// density of 1e6: with w = 1 + g^2 - 2 g c = (1 - g)^2 + 2 g (1 - c),
//   CDF(c) = (1 - g)(1 + c) / (sqrt(w) (1 + g + sqrt(w)))
// (the classic (1 - g^2) / (2 g) (1 / sqrt(w) - 1 / (1 + g)) with the
// difference rationalized), and its inverse, with D = 1 - g + 2 g u and
// s = (1 - g^2) / D,
//   c = 1 - (1 - g)(1 - u)(s + 1 - g) / D
// (the classic (1 + g^2 - s^2) / (2 g) with s^2 - (1 - g)^2 factored).

inline double henyey_greenstein_w(double c, double g) {
  return (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - c);
}
inline double henyey_greenstein_cosine_pdf(double c, double g) {
  const double w = henyey_greenstein_w(c, g);
  return (1.0 - g * g) / (2.0 * w * std::sqrt(w));
}
inline double henyey_greenstein_cosine_cdf(double c, double g) {
  c = clamp_cosine(c);
  const double root = std::sqrt(henyey_greenstein_w(c, g));
  return (1.0 - g) * (1.0 + c) / (root * (1.0 + g + root));
}
inline double henyey_greenstein_cosine_from_cdf(double u, double g) {
  const double d = 1.0 - g + 2.0 * g * u;
  const double s = (1.0 - g * g) / d;
  return clamp_cosine(1.0 - (1.0 - g) * (1.0 - u) * (s + 1.0 - g) / d);
}

// ---- Cornette-Shanks --------------------------------------------------------

inline double cornette_shanks_cosine_pdf(double c, double g) {
  const double w = henyey_greenstein_w(c, g);
  return 0.75 * (1.0 - g * g) * (1.0 + c * c) / ((2.0 + g * g) * w * std::sqrt(w));
}
// Rejection from HG; `uniform` returns numbers in [0, 1).
template <typename Uniform>
double sample_cornette_shanks_cosine(double g, Uniform& uniform) {
  for (;;) {
    const double c = henyey_greenstein_cosine_from_cdf(uniform(), g);
    if (2.0 * uniform() < 1.0 + c * c) return c;
  }
}

// ---- Any component ----------------------------------------------------------

// A cosine distributed as the component's phase function. Components that
// only absorb never scatter; asking is a programmer error.
template <typename Uniform>
double sample_phase_cosine(PhaseKind kind, double g, Uniform& uniform) {
  switch (kind) {
    case PhaseKind::rayleigh:
      return rayleigh_cosine_from_cdf(uniform());
    case PhaseKind::henyey_greenstein:
      return henyey_greenstein_cosine_from_cdf(uniform(), g);
    case PhaseKind::cornette_shanks:
      return sample_cornette_shanks_cosine(g, uniform);
    case PhaseKind::none:
      break;
  }
  assert(false && "sample_phase_cosine: the component does not scatter");
  return 1.0;
}

// ---- Directions -------------------------------------------------------------

// The unit vector at cosine c from the unit vector `axis`, at azimuth
// 2 pi u_azimuth around it (frame of Duff et al. 2017, "Building an
// orthonormal basis, revisited", continuous except at axis.z = 0 sign flips).
inline glm::dvec3 direction_from_cosine(glm::dvec3 axis, double c, double u_azimuth) {
  const double sign = std::copysign(1.0, axis.z);
  const double a = -1.0 / (sign + axis.z);
  const double b = axis.x * axis.y * a;
  const glm::dvec3 t1(1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
  const glm::dvec3 t2(b, sign + axis.y * axis.y * a, -axis.y);
  const double s = safe_sqrt(1.0 - c * c), phi = 2.0 * kPi * u_azimuth;
  return glm::normalize(s * (std::cos(phi) * t1 + std::sin(phi) * t2) + c * axis);
}

// A cosine-weighted direction around the unit normal n (density
// cos(theta) / pi over the hemisphere): the Lambertian ground's bounce.
template <typename Uniform>
glm::dvec3 sample_cosine_hemisphere(glm::dvec3 n, Uniform& uniform) {
  const double c = std::sqrt(uniform());
  return direction_from_cosine(n, c, uniform());
}

}  // namespace skybake

// A thin slab of dust lit by the sun: its first two scattering orders from
// closed forms and quadrature, independent of every table (the tests of the
// 4D orders on a sharp forward lobe: thin_slab_orders_test.cpp and its
// accuracy twin).
//
// The slab: plane-parallel, z from 0 (a black ground) to H, a uniform medium
// of scattering coefficient sigma and no absorption, phase p (Henyey-
// Greenstein), sun of cosine mu_s and illuminance 1. Light travels along
// -s, s the direction toward the sun. Radiance travelling along w (w_z = m)
// at height z, single scattering, with tau_s = sigma (H - z) / mu_s:
//   m < 0: L1 = sigma p(-s.w) exp(-tau_s) int_0^D exp(k t) dt,
//          D = (H - z) / |m|, k = sigma (|m| / mu_s - 1);
//   m > 0: L1 = sigma p(-s.w) exp(-tau_s) int_0^D exp(-k t) dt,
//          D = z / m, k = sigma (m / mu_s + 1);
// both tend to p exp(-tau_s) as m -> 0 (the ray runs inside the slab).
// The second order reaching the ground along -v (v the view, v_z > 0):
//   L2 = int_0^{H / v_z} exp(-sigma t) J(t v_z, -v) dt,
//   J(z, w) = sigma int_{4 pi} p(w'.w) L1(z, w') dw',
// the sphere integral in a frame around w (the lobe's peak on its axis):
// Gauss-Legendre panels in cos(alpha), denser toward the peak, and equal
// steps in the azimuth.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/phase.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "core/math.hpp"

namespace skybake::thin_slab {

// Gauss-Legendre on [0, 1]: nodes x, weights w (summing to 1).
struct Rule01 {
  std::vector<double> x, w;
  explicit Rule01(int n) {
    gauss_legendre(n, x, w);
    for (size_t i = 0; i < x.size(); ++i) x[i] = 0.5 + 0.5 * x[i], w[i] *= 0.5;
  }
};

struct Slab {
  double height_m = 10e3;
  double sigma_per_m = 2e-5;  // vertical optical depth 0.2
  double g = 0.85;
  glm::dvec3 sun{0.0, 0.0, 1.0};  // toward the sun, unit, z up
};

// int_0^D exp(k t) dt, stable for small k D.
inline double exp_integral(double k, double d) {
  const double x = k * d;
  return std::abs(x) < 1e-8 ? d * (1.0 + 0.5 * x) : std::expm1(x) / k;
}

// L1 at height z along the travelling direction w (unit).
inline double single(const Slab& s, double z, const glm::dvec3& w) {
  const double mu_s = s.sun.z, m = w.z, sigma = s.sigma_per_m;
  const double lit = sigma * henyey_greenstein_phase(-glm::dot(s.sun, w), s.g) *
                     std::exp(-sigma * (s.height_m - z) / mu_s);
  if (m < -1e-12) return lit * exp_integral(sigma * (-m / mu_s - 1.0), (s.height_m - z) / -m);
  if (m > 1e-12) return lit * exp_integral(-sigma * (m / mu_s + 1.0), z / m);
  return lit / sigma;
}

// J(z, w): sigma int p(w'.w) L1(z, w') dw'.
inline double source(const Slab& s, double z, const glm::dvec3& w, int azimuths = 720) {
  const glm::dvec3 e1 = glm::normalize(std::abs(w.x) < 0.9 ? glm::cross(w, glm::dvec3(1, 0, 0))
                                                           : glm::cross(w, glm::dvec3(0, 1, 0)));
  const glm::dvec3 e2 = glm::cross(w, e1);
  // cos(alpha) panels: the peak of g = 0.85 is some 0.1 rad wide.
  static const double edges[] = {-1.0, 0.0, 0.7, 0.9, 0.97, 0.99, 0.997, 0.9995, 1.0};
  static const Rule01 rule(24);
  double sum = 0.0;
  for (size_t p = 0; p + 1 < std::size(edges); ++p) {
    const double a = edges[p], b = edges[p + 1];
    for (size_t i = 0; i < rule.x.size(); ++i) {
      const double u = a + (b - a) * rule.x[i], sin_alpha = std::sqrt(std::max(0.0, 1.0 - u * u));
      double ring = 0.0;
      for (int k = 0; k < azimuths; ++k) {
        const double phi = 2.0 * kPi * (k + 0.5) / azimuths;
        const glm::dvec3 w_in = u * w + sin_alpha * (std::cos(phi) * e1 + std::sin(phi) * e2);
        ring += single(s, z, w_in);
      }
      sum += (b - a) * rule.w[i] * henyey_greenstein_phase(u, s.g) * ring * (2.0 * kPi / azimuths);
    }
  }
  return s.sigma_per_m * sum;
}

// L2 at the ground toward the view v (unit, v.z > 0).
inline double second_order_at_ground(const Slab& s, const glm::dvec3& v, int azimuths = 720) {
  const double length = s.height_m / v.z;
  static const Rule01 rule(16);
  double sum = 0.0;
  for (size_t i = 0; i < rule.x.size(); ++i) {
    const double t = length * rule.x[i];
    sum += length * rule.w[i] * std::exp(-s.sigma_per_m * t) * source(s, t * v.z, -v, azimuths);
  }
  return sum;
}

// L1 at the ground toward the view v, in closed form.
inline double single_at_ground(const Slab& s, const glm::dvec3& v) {
  return single(s, 0.0, -v);
}

}  // namespace skybake::thin_slab

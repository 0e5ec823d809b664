// Optical depth in closed form of the components whose density profile has
// no exponential term (every layer's exp_term == 0: Hillaire's ozone tent,
// uniform slabs). Along a straight ray the radius is r(x) = sqrt(x^2 + p^2),
// x the signed distance from the perigee and p the perigee's radius, and such
// a density is c (r - Rb) + d, 0 or 1 between two kink altitudes, so its
// integral is elementary: docs/reference.md "Transmittance", "Linear layers
// in closed form". The transmittance table's rule integrates these
// components this way and the exponential ones by quadrature.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"

namespace skybake {

// x1 - x0 and r1 - r0 for 0 <= x0 <= x1 on a ray of perigee radius p, from
// ends with r = sqrt(x^2 + p^2). Either pair is exact to rounding and the
// other is derived from it through (x1 - x0)(x1 + x0) = (r1 - r0)(r1 + r0):
// the radii where both ends are a kink's radius or the perigee (their x,
// sqrt((R - p)(R + p)), carries ~eps x of rounding, which far from the
// perigee is much more than eps (x1 - x0)); else the distances (near the
// perigee r1 - r0 is small next to the rounding of a computed r).
struct Chord {
  double length, dr;
};
Chord chord(double x0, double r0, double x1, double r1, bool radii_exact);

// int_{x0}^{x1} (sqrt(x^2 + p^2) - R) dx for 0 <= x0 <= x1, given
// r0 = sqrt(x0^2 + p^2) and r1 = sqrt(x1^2 + p^2) (m^2). With
// L, dr = chord(...) the form
//   (L (r1 - R) + x0 dr + p^2 log1p((L + dr) / (x0 + r0)) - R L) / 2
// is the antiderivative (x r + p^2 asinh(x / p)) / 2 - R x differenced
// without subtracting two large values of x r or of asinh; it holds at
// p = 0 (docs/reference.md eq. T2). p^2 log1p(.) and R L are ~R L each where
// the result is ~h L (h the altitude above R), so an error in L counts R /
// h times: hence chord's choice of the exact pair.
double radius_excess_integral(double p, double x0, double r0, double x1, double r1, double R,
                              bool radii_exact);
// The same with the chord already taken (c = chord(x0, r0, x1, r1, radii_exact)).
double radius_excess_integral(double p, double x0, double r0, double r1, double R, Chord c);

class LinearLayerDepth {
 public:
  // The components of `atm` with extinction and a piecewise-linear profile
  // (is_piecewise_linear); the others are left to the caller.
  explicit LinearLayerDepth(const Atmosphere& atm);

  bool empty() const { return bands_.empty(); }

  // Optical depth (RGB) of those components along the segment of length d
  // (m) from radius r (m) with zenith cosine mu. The segment must stay at or
  // above the ground: altitudes below 0 continue the lowest band's formula.
  glm::dvec3 integrate(double r, double mu, double d) const;

 private:
  // Between two consecutive kink radii of the linear components every
  // component is linear, 0 or 1 throughout: the band's extinction is
  // slope (r - Rb) + constant, summed over components (1/m^2 and 1/m).
  struct Band {
    double top_radius;  // m; +inf for the last band
    glm::dvec3 slope, constant;
    bool empty;  // slope and constant 0: no component has extinction here
  };
  struct Ray {
    double r, x_start;  // start radius, signed distance from the perigee (r mu)
    double p, p2;       // perigee radius, squared
  };
  void add_interval(const Ray& ray, double lo, double hi, double weight, glm::dvec3& tau) const;

  double bottom_radius_;
  std::vector<Band> bands_;  // from the ground up; empty when no component is linear
};

}  // namespace skybake

// Closed-form optical depth of piecewise-linear density profiles
// (docs/reference.md "Transmittance", "Linear layers in closed form").
#include "atmosphere/linear_layer_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/density_kinks.hpp"
#include "core/math.hpp"

namespace skybake {

Chord chord(double x0, double r0, double x1, double r1, bool radii_exact) {
  if (radii_exact) {
    const double dr = r1 - r0;
    return {x0 + x1 > 0.0 ? dr * (r1 + r0) / (x0 + x1) : 0.0, dr};
  }
  const double length = x1 - x0;
  return {length, r0 + r1 > 0.0 ? length * (x0 + x1) / (r0 + r1) : 0.0};
}

double radius_excess_integral(double p, double x0, double r0, double x1, double r1, double R,
                              bool radii_exact) {
  return radius_excess_integral(p, x0, r0, r1, R, chord(x0, r0, x1, r1, radii_exact));
}

double radius_excess_integral(double p, double x0, double r0, double r1, double R, Chord c) {
  const auto [length, dr] = c;
  // asinh(x1 / p) - asinh(x0 / p) = log((x1 + r1) / (x0 + r0)); x0 + r0 > 0
  // unless the ray passes through the centre (p = 0), where p^2 times it is 0.
  const double log_ratio = p > 0.0 ? std::log1p((length + dr) / (x0 + r0)) : 0.0;
  return 0.5 * (length * (r1 - R) + x0 * dr + p * p * log_ratio - R * length);
}

LinearLayerDepth::LinearLayerDepth(const Atmosphere& atm) : bottom_radius_(atm.bottom_radius_m) {
  const double top_h = atm.top_radius_m - atm.bottom_radius_m;
  std::vector<const MediumComponent*> linear;
  std::vector<double> kinks;
  for (const MediumComponent& c : atm.components) {
    const glm::dvec3 sigma_t = c.scattering_per_m + c.absorption_per_m;
    if (sigma_t == glm::dvec3(0.0) || c.density.layers.empty() ||
        !is_piecewise_linear(c.density))
      continue;
    linear.push_back(&c);
    add_profile_kinks(c.density, top_h, kinks);
  }
  if (linear.empty()) return;
  std::sort(kinks.begin(), kinks.end());
  kinks.erase(std::unique(kinks.begin(), kinks.end()), kinks.end());
  // Each band's state is read at its middle: no formula crosses 0 or 1 and
  // no layer ends strictly inside a band.
  for (size_t i = 0; i <= kinks.size(); ++i) {
    const double lo = i == 0 ? 0.0 : kinks[i - 1];
    const double hi = i == kinks.size() ? top_h : kinks[i];
    const double h = 0.5 * (lo + hi);
    Band band{i == kinks.size() ? std::numeric_limits<double>::infinity()
                                : atm.bottom_radius_m + hi,
              glm::dvec3(0.0), glm::dvec3(0.0), false};
    for (const MediumComponent* c : linear) {
      const DensityLayer& l = layer_at(c->density, h);
      const glm::dvec3 sigma_t = c->scattering_per_m + c->absorption_per_m;
      const double v = l.linear_term_per_m * h + l.constant_term;
      if (v >= 1.0) {
        band.constant += sigma_t;
      } else if (v > 0.0) {  // c h + d = c (r - Rb) + d
        band.slope += sigma_t * l.linear_term_per_m;
        band.constant += sigma_t * l.constant_term;
      }
    }
    band.empty = band.slope == glm::dvec3(0.0) && band.constant == glm::dvec3(0.0);
    bands_.push_back(band);
  }
}

// Adds weight times the optical depth of the ray's points at distances
// x in [lo, hi] from the perigee (0 <= lo <= hi), band by band. The band
// below radius R ends at x = sqrt(r^2 mu^2 + (R - r)(R + r)), which is
// sqrt(R^2 - p^2) but keeps its digits where the ray grazes R: there
// (R - p)(R + p) would carry p's rounding, eps r, times 2R (a chord off by
// ~10 cm through a sphere it grazes).
void LinearLayerDepth::add_interval(const Ray& ray, double lo, double hi, double weight,
                                    glm::dvec3& tau) const {
  double x_bottom = 0.0, r_bottom = ray.p;  // the band holding the perigee starts there
  bool bottom_is_kink = false;
  for (const Band& band : bands_) {
    const bool last = std::isinf(band.top_radius);
    const double R = band.top_radius;
    const double disc = last ? 0.0 : ray.x_start * ray.x_start + (R - ray.r) * (R + ray.r);
    if (!last && disc <= 0.0) continue;  // the ray passes above this band
    const double x_top = last ? hi : std::sqrt(disc);
    const double x0 = std::max(x_bottom, lo), x1 = std::min(x_top, hi);
    // A band where every component is 0 adds +0 to tau, which changes no bit.
    if (x1 > x0 && !band.empty) {
      const double r0 = x0 == x_bottom ? r_bottom : std::sqrt(x0 * x0 + ray.p2);
      const double r1 = x1 == x_top && !last ? R : std::sqrt(x1 * x1 + ray.p2);
      // Radii are exact at kinks, not at the perigee (p is rounded) nor at
      // the ray's ends.
      const bool radii_exact = x0 == x_bottom && bottom_is_kink && x1 == x_top && !last;
      const Chord c = chord(x0, r0, x1, r1, radii_exact);
      tau += (weight * c.length) * band.constant;
      if (band.slope != glm::dvec3(0.0))
        tau += (weight * radius_excess_integral(ray.p, x0, r0, r1, bottom_radius_, c)) *
               band.slope;
    }
    if (x_top >= hi) break;
    x_bottom = x_top;
    r_bottom = R;
    bottom_is_kink = true;
  }
}

glm::dvec3 LinearLayerDepth::integrate(double r, double mu, double d) const {
  glm::dvec3 tau(0.0);
  if (bands_.empty() || !(d > 0.0)) return tau;
  Ray ray;
  ray.r = r;
  ray.x_start = r * mu;  // the segment's ends, measured from the perigee: x_start, x_start + d
  ray.p2 = r * r * std::max(0.0, (1.0 - mu) * (1.0 + mu));
  ray.p = std::sqrt(ray.p2);
  const double xa = ray.x_start, xb = xa + d;
  if (xa < 0.0 && xb > 0.0) {
    // Through the perigee: the part mirrored on both sides counts twice.
    const double shorter = std::min(-xa, xb), longer = std::max(-xa, xb);
    add_interval(ray, 0.0, shorter, 2.0, tau);
    add_interval(ray, shorter, longer, 1.0, tau);
  } else {
    const double a = std::abs(xa), b = std::abs(xb);
    add_interval(ray, std::min(a, b), std::max(a, b), 1.0, tau);
  }
  return tau;
}

}  // namespace skybake

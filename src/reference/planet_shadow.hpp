// The part of a straight segment that lies in the planet's shadow, in
// closed form, for the path tracer's segment estimate of the sun
// (path_tracer.hpp). A point p is in the shadow of a directional sun l
// when its ray toward the sun meets the ground: p . l < 0 (the point is
// on the night side of the plane through the planet's centre) and its
// distance to the axis through the centre along l is below the planet's
// radius, |p|^2 - (p . l)^2 < Rb^2 (inside the shadow cylinder). Along p(s)
// = o + s w the second condition is a quadratic in s and the first a
// half-line, so the shadow is one interval and the lit part at most two.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace skybake {

struct ShadowInterval {
  double begin = 0.0, end = 0.0;  // [begin, end) within [0, length]; empty when begin >= end
  bool empty() const { return !(begin < end); }
};

// The shadowed part of p(s) = origin + s dir, s in [0, length]; dir and
// sun_dir unit vectors, origin planet-centred (m), bottom_m the planet's
// radius.
inline ShadowInterval planet_shadow_interval(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 sun_dir,
                                             double bottom_m, double length) {
  const double nu = glm::dot(dir, sun_dir), o_l = glm::dot(origin, sun_dir);
  // The cylinder: a s^2 + 2 b s + c < 0.
  const double a = std::max(1.0 - nu * nu, 0.0);
  const double b = glm::dot(origin, dir) - o_l * nu;
  const double c = glm::dot(origin, origin) - o_l * o_l - bottom_m * bottom_m;
  double lo = 0.0, hi = length;
  if (a <= 1e-15) {  // parallel to the axis: inside the cylinder everywhere or nowhere
    if (!(c < 0.0)) return {};
  } else {
    const double discriminant = b * b - a * c;
    if (!(discriminant > 0.0)) return {};
    const double q = std::sqrt(discriminant);
    lo = std::max(lo, (-b - q) / a);
    hi = std::min(hi, (-b + q) / a);
  }
  // The night side: o . l + s nu < 0.
  if (nu > 0.0) {
    hi = std::min(hi, -o_l / nu);
  } else if (nu < 0.0) {
    lo = std::max(lo, -o_l / nu);
  } else if (!(o_l < 0.0)) {
    return {};
  }
  if (!(lo < hi)) return {};
  return {lo, hi};
}

}  // namespace skybake

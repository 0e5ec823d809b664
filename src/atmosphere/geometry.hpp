// Ray / sphere distances for a viewer at radius r looking along a direction of
// cosine mu with the local zenith (Bruneton 2017, "Distance to the top/bottom
// atmosphere boundary"). Written to stay exact near the horizon and at the
// boundaries: discriminants go through safe_sqrt and results are clamped to 0.
#pragma once

#include "core/math.hpp"

namespace skybake {

// Distance from (r, mu) to the sphere of radius top_m along the ray, for r <= top_m.
inline double distance_to_top_boundary(double top_m, double r, double mu) {
  const double discriminant = r * r * (mu * mu - 1.0) + top_m * top_m;
  return std::max(0.0, -r * mu + safe_sqrt(discriminant));
}

// Distance from (r, mu) to the ground sphere of radius bottom_m (first hit),
// for r >= bottom_m; meaningful only when ray_intersects_ground.
inline double distance_to_bottom_boundary(double bottom_m, double r, double mu) {
  const double discriminant = r * r * (mu * mu - 1.0) + bottom_m * bottom_m;
  return std::max(0.0, -r * mu - safe_sqrt(discriminant));
}

// True when the ray (r, mu) hits the ground: it points down and the ground
// sphere is in front of it.
inline bool ray_intersects_ground(double bottom_m, double r, double mu) {
  return mu < 0.0 && r * r * (mu * mu - 1.0) + bottom_m * bottom_m >= 0.0;
}

// Distance to where the ray leaves the atmosphere or meets the ground.
inline double distance_to_nearest_boundary(double bottom_m, double top_m, double r, double mu,
                                           bool hits_ground) {
  return hits_ground ? distance_to_bottom_boundary(bottom_m, r, mu)
                     : distance_to_top_boundary(top_m, r, mu);
}

// Radius and zenith cosine after travelling distance d along (r, mu)
// (law of cosines); the square root is safe, callers clamp to the shell.
// Zenith cosine of the horizon seen from radius r >= bottom_m:
// -sqrt(r^2 - Rb^2) / r; views below it meet the ground.
inline double horizon_zenith_cosine(double bottom_m, double r) {
  return -std::sqrt(std::max((r - bottom_m) * (r + bottom_m), 0.0)) / r;
}

inline double radius_after(double r, double mu, double d) {
  return safe_sqrt(d * d + 2.0 * r * mu * d + r * r);
}
inline double mu_after(double r, double mu, double d, double r_d) {
  return r_d > 0.0 ? clamp_cosine((r * mu + d) / r_d) : 1.0;
}

}  // namespace skybake

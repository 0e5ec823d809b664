// Small numeric helpers that clamp their domain first (after Bruneton's
// ClampCosine / SafeSqrt): geometry near the horizon and at the boundaries
// produces arguments a rounding error outside their domain.
#pragma once

#include <algorithm>
#include <cmath>

namespace skybake {

constexpr double kPi = 3.14159265358979323846;
// Radians per degree: presets give angles in degrees.
constexpr double kDeg = kPi / 180.0;

inline double clamp_cosine(double mu) { return std::clamp(mu, -1.0, 1.0); }
inline double safe_sqrt(double a) { return std::sqrt(std::max(a, 0.0)); }

// Texel-centre mapping (docs/architecture.md "Texel centres"): x in [0, 1] covers the texel
// centres of an n-texel axis exactly, so x = 0 and x = 1 land on the first and
// last texel centres. Bruneton 2017 GetTextureCoordFromUnitRange.
inline double texel_coord_from_unit(double x, int n) { return 0.5 / n + x * (1.0 - 1.0 / n); }
inline double unit_from_texel_coord(double u, int n) { return (u - 0.5 / n) / (1.0 - 1.0 / n); }
// The texture coordinate of texel i's centre.
inline double texel_center(int i, int n) { return (i + 0.5) / n; }

// Floor-based modulo: result in [0, m) for any sign of a (C's % and fmod are not).
inline int wrap_index(int a, int m) {
  const int r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace skybake

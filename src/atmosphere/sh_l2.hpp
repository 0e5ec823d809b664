// Real spherical harmonics to band 2 (9 functions) and the clamped-cosine
// convolution of Ramamoorthi & Hanrahan 2001 ("An Efficient Representation
// for Irradiance Environment Maps", eq. 3, 7-9): docs/reference.md
// "Sky irradiance (L2 SH)".
//
// Index k = l (l + 1) + m, directions (x, y, z) unit length:
//   0: Y_00 = 0.282095              1: Y_1-1 = 0.488603 y
//   2: Y_10 = 0.488603 z            3: Y_11  = 0.488603 x
//   4: Y_2-2 = 1.092548 x y         5: Y_2-1 = 1.092548 y z
//   6: Y_20 = 0.315392 (3 z^2 - 1)  7: Y_21  = 1.092548 x z
//   8: Y_22 = 0.546274 (x^2 - y^2)
// Irradiance from radiance coefficients L_lm: E(n) = sum A_l L_lm Y_lm(n)
// with A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (R&H 2001 eq. 8).
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "core/math.hpp"

namespace skybake {

constexpr int kShL2Count = 9;

// sqrt(1 / (4 pi)), sqrt(3 / (4 pi)), sqrt(15 / (4 pi)), sqrt(5 / (16 pi)),
// sqrt(15 / (16 pi)): the normalisations of the real basis above.
constexpr double kShY00 = 0.28209479177387814;
constexpr double kShY1 = 0.48860251190291992;
constexpr double kShY2a = 1.0925484305920792;
constexpr double kShY20 = 0.31539156525252005;
constexpr double kShY22 = 0.54627421529603959;

// R&H 2001 eq. 8, per band l = 0, 1, 2.
constexpr double kShCosineBand[3] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0};

inline int sh_band(int k) { return k == 0 ? 0 : (k < 4 ? 1 : 2); }

inline std::array<double, kShL2Count> sh_l2_basis(glm::dvec3 d) {
  return {kShY00,
          kShY1 * d.y,
          kShY1 * d.z,
          kShY1 * d.x,
          kShY2a * d.x * d.y,
          kShY2a * d.y * d.z,
          kShY20 * (3.0 * d.z * d.z - 1.0),
          kShY2a * d.x * d.z,
          kShY22 * (d.x * d.x - d.y * d.y)};
}

// The coefficients of a field symmetric about the x-z plane (f(x, y, z) =
// f(x, -y, z): a sky with the sun in that plane): the functions odd in y
// (k = 1, 4, 5) integrate to 0 against it, the other six are stored, in
// this order.
constexpr int kShSymmetricCount = 6;
constexpr int kShSymmetricIndex[kShSymmetricCount] = {0, 2, 3, 6, 7, 8};

// Irradiance E(n) = sum_k A_l(k) L_k Y_k(n) from radiance coefficients.
inline glm::dvec3 sh_l2_irradiance(const std::array<glm::dvec3, kShL2Count>& radiance,
                                   glm::dvec3 n) {
  const std::array<double, kShL2Count> y = sh_l2_basis(n);
  glm::dvec3 e(0.0);
  for (int k = 0; k < kShL2Count; ++k) e += kShCosineBand[sh_band(k)] * y[k] * radiance[k];
  return e;
}

}  // namespace skybake

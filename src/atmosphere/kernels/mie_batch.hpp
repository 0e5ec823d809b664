// The Mie part of the scattering density of the 4D table (scattering_
// density.cpp): sum_j k(v . w_j) L_j dw_j over the density's direction grid
// for one view v, the one loop of the bake that runs (texels x directions)
// times, 0.27 G direction pairs per order at default sizes. It runs in single
// precision, eight pairs per step (lanes accumulate ~32 terms each: relative
// rounding ~1e-6, well below the quadrature's error), over lanes (Highway):
// the same bits on every target (tests/atmosphere/kernels_test.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/incident_radiance.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

// The part of the Mie phase that does not cancel in the normalized
// quadrature: Cornette-Shanks (1 + c^2) / w^1.5, Henyey-Greenstein 1 / w^1.5,
// w = 1 + g^2 - 2 g c (phase.hpp up to constant factors), written
// w = (1 - g)^2 + 2 g (1 - c) so that it stays > 0 in single precision for
// g -> 1 (g = 0.999: w = 1e-6 in the forward direction, where 1 + g^2 - 2 g c
// would cancel to rounding noise or below zero).
struct MieKernel {
  double a = 1.0, b = 0.0;  // (1 - g)^2, 2 g
  bool cornette_shanks = true;
  explicit MieKernel(const ScatteringPhases& p)
      : a((1.0 - p.mie_g) * (1.0 - p.mie_g)),
        b(2.0 * p.mie_g),
        cornette_shanks(p.mie_phase == PhaseKind::cornette_shanks) {}
};

// The grid and one incident field as float arrays. The field is symmetric
// about the sun's vertical plane (azimuths m and azimuths - 1 - m hold the
// same radiance, compute_incident_radiance), so a direction and its mirror
// (x, -y, z) are one pair: one load of the field, and their two phases over
// one division,
//   k+ + k- = (n+ q- + n- q+) / (q+ q-),  k = n / q,  q = w^1.5.
// Pairs padded to a multiple of 8 with zero weights; pair j adds into lane
// j % 8 of each sum, and the lanes are added in double at the end. The
// field and weights are stored by blocks of 8 pairs, R G B and dw of one
// block together (field()).
struct MieBatch {
  static constexpr size_t kLanes = 8;
  size_t n = 0;
  std::vector<size_t> first;  // grid index of each pair's direction with y > 0
  std::vector<float> x, y, z;
  std::vector<float> blocks;  // per block of 8 pairs: L_R dw, L_G dw, L_B dw, dw (8 each)
  // Channel c (R, G, B, weight) of pair j.
  static size_t field(int c, size_t j) { return 32 * (j / 8) + 8 * size_t(c) + j % 8; }

  explicit MieBatch(const SphereGrid& grid);
  // The pair's mean radiance (the two are equal for the density's fields).
  void set_field(const std::vector<glm::dvec3>& L);
  // sum_j k(v . w_j) L_j dw_j (RGB) and sum_j k(v . w_j) dw_j (out[3]),
  // over both directions of every pair.
  void sums(const MieKernel& k, const glm::dvec3& v, double out[4]) const;

 private:
  size_t grid_azimuths = 0;
};

}  // namespace skybake

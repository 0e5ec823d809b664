// One quadrature node of a texel row of the multiple-scattering pass
// (multiple_scattering.cpp): the texels' sun cosine at the node, its mu_s
// taps and the bilinear read of the node's blended slice (row_blend.hpp).
// The cosine is taken in double; the mu_s mapping of Bruneton 2017
// (GetTextureCoordFromUnitRange of GetScatteringTextureUvwzFromRMuMuSNu, at
// r = bottom) in single precision, as many texels as the target has float
// lanes: the square root and the division of the mapping are the loop's
// limit (the divider), and in float they cost about a third of the double
// ones. Every target does the same IEEE operations per lane, so the same
// bits (tests/atmosphere/kernels_test.cpp).
#pragma once

#include "atmosphere/kernels/row_blend.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

// The mu_s mapping as one division: with D = Rb m + sqrt(Rb^2 m^2 + H^2),
// the distance to the top is d = H^2 / D (no cancellation near m = 1, where
// -Rb m + sqrt(..) loses two digits in float), and
//   u = max(1 - a / A, 0) / (1 + a), a = (d - d_min) / span,
// becomes u = max(D k1 - h2, 0) / (D ak2 + ah2), every length in units of
// Rb (k1 = (A span + d_min) / Rb, ak2 = A (span - d_min) / Rb, h2 = H^2 /
// Rb^2, ah2 = A h2). Within 2.5e-5 of a texel of MuSAxis::tap (tested; 5e-6
// on Earth's default 32 texels); the reads' weights are floats either way.
struct SunCosineTapsFloat {
  float lo = -1, h2 = 0, k1 = 0, ak2 = 0, ah2 = 0, last = 0, below_last = 0;
  explicit SunCosineTapsFloat(const MuSAxis::Constants& c);
  // The tap of one cosine (unclamped), the operations of the loops: texel
  // i0 (i1 = i0 + 1) and the weight of i1.
  void tap(double mu_s, int& i0, float& w) const;
};

// The node and the row's per-texel constants. The per-texel arrays hold a
// multiple of 8 texels (padded with valid values: the loops compute whole
// groups, and the padded lanes' sums are not read). The first `single`
// texels (a multiple of 8) read one nu slice, nu_i0 (their nu_w is 0): a
// texel whose nu is a slice's own reads the other slice with a weight of 0
// (or the same with 1 - 1), and lerp(a, b, 0) = 1 a + 0 b = a exactly for
// finite values, so one read gives the same bits at half the loads.
struct NodeRow {
  double r = 0, s = 0, inv_r_i = 0;  // the ray's start radius, the node's distance along it, 1 / its radius
  int single = 0;
  const double* mu_s = nullptr;  // per texel: mu_s and nu of the texel
  const double* nu = nullptr;
  const int* nu_i0 = nullptr;  // per texel: the nu slices' offsets and weight (nu_slice_tap)
  const int* nu_i1 = nullptr;
  const float* nu_w = nullptr;
  int *at0 = nullptr, *at1 = nullptr;  // work arrays of the padded size: the reads' texels
  float* lw = nullptr;                 // and mu_s weights
};

// For texels [0, end), end a multiple of 8: sum[x] += wS lerp(lerp(s00,
// s01, lw), lerp(s10, s11, lw), nw), s00 = slice[nu_i0[x] + i0], s10 =
// slice[nu_i1[x] + i0], s01 and s11 the next texels along mu_s, (i0, lw) the
// taps of clamp_cosine((r mu_s[x] + s nu[x]) inv_r_i) (SunCosineTapsFloat::tap);
// for x < single, sum[x] += wS lerp(s00, s01, lw).
void add_node_slice_reads(const NodeRow& row, const SunCosineTapsFloat& taps, const Rgb4* slice, const Rgb4& wS,
                  int end, Rgb4* sum);

}  // namespace skybake

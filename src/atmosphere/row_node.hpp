// One quadrature node of a texel row of the multiple-scattering pass
// (multiple_scattering.cpp) in a single AVX2 loop: the texels' sun cosine at
// the node (mu_s_at_node), its mu_s taps (MuSAxis::taps) and the bilinear
// read of the blended slice (add_bilinear_row), four texels at a time. The
// same operations per lane as those three passes, so the same values
// (core/wide_vectors.hpp). In one loop the divider's work (two divisions and
// a square root per texel, in double) overlaps the loads and shuffles of the
// reads, where the three passes ran one after the other.
#pragma once

#include "atmosphere/row_blend.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

// The node and the row's per-texel constants.
struct NodeRow {
  double r = 0, s = 0, inv_r_i = 0;  // the ray's start radius, the node's distance along it, 1 / its radius
  const double* mu_s = nullptr;  // per texel: mu_s and nu of the texel (mu_s_at_node)
  const double* nu = nullptr;
  const int* nu_i0 = nullptr;  // per texel: the nu slices' offsets and weight (BilinearTaps)
  const int* nu_i1 = nullptr;
  const float* nu_w = nullptr;
  int *at0 = nullptr, *at1 = nullptr;  // work arrays of the row's size: the reads' texels
  float* lw = nullptr;                 // and mu_s weights
};

// For the first texels of the row (a multiple of 4; none without AVX2):
// sum[x] += wS lerp(lerp(s00, s01, lw), lerp(s10, s11, lw), nw) with the taps
// of MuSAxis::taps at mu_s_at_node(r, s, inv_r_i, mu_s[x], nu[x]), the same
// values as the three passes. Returns how many texels it did.
int add_node_row(const NodeRow& row, const MuSAxis& axis, const Rgb4* slice, const Rgb4& wS, int n,
                 Rgb4* sum);

}  // namespace skybake

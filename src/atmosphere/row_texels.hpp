// The texels of one row (r, mu) of the multiple-scattering pass as its node
// loop reads them (kernels/node_slice_reads.hpp): each texel's mu_s and nu, which are the
// same at every node of the ray, and its nu slices.
#pragma once

#include <vector>

#include "atmosphere/kernels/node_slice_reads.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

struct RowTexels {
  // Per computed texel (NodeRow's arrays; at0, at1 and lw are the loop's).
  std::vector<double> mu_s, nu;
  std::vector<int> nu_i0, nu_i1, at0, at1;
  std::vector<float> nu_w, lw;
  // Per texel of the row: where its value is computed. Slices whose nu
  // clamps to the same value (texels.at) are the same texel, computed once.
  std::vector<int> slot;
  // The computed texels: [0, single) read one nu slice, [single, end) two,
  // each group padded to a multiple of 8 with valid texels.
  int single = 0, end = 0;

  explicit RowTexels(const ScatteringShape& shape);
  // The row's texels at view cosine mu: texels.params(x, y, z) for every x,
  // with the spread of nu once per mu_s texel.
  void make(const ScatteringTexelGrid& texels, const ScatteringShape& shape, double mu);
  NodeRow node(double r, double s, double inv_r_i);

 private:
  struct Staged {
    double mu_s = 0, nu = 0;
    int nu_i0 = 0, nu_i1 = 0;
    float nu_w = 0;
  };
  std::vector<double> spread_;
  std::vector<Staged> staged_;  // the distinct texels in row order
  std::vector<int> place_;      // and where each goes
};

}  // namespace skybake

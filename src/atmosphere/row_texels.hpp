// The texels of one row (r, mu) of the multiple-scattering pass as its node
// loop reads them (kernels/node_slice_reads.hpp): each texel's mu_s and nu, which are the
// same at every node of the ray, and its nu slices.
#pragma once

#include <vector>

#include "atmosphere/kernels/node_slice_reads.hpp"
#include "atmosphere/kernels/sun_frame_reads.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sun_frame_density.hpp"

namespace skybake {

struct RowTexels {
  // Per computed texel (NodeRow's arrays; at0, at1 and lw are the loop's).
  std::vector<double> mu_s, nu;
  std::vector<int> nu_i0, nu_i1, at0, at1;
  std::vector<float> nu_w, lw;
  // For the reads in the sun's frame (SunFrameNode): nu and sin_nu in
  // float, the density's nu nodes (sun_frame_nu_grid, as offsets m *
  // mu_s_size) and the weight of the second, the cos_phi weights.
  std::vector<float> nu_f, sin_nu, sun_nu_w, pw;
  std::vector<int> sun_nu_i0, sun_nu_i1;
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
  // After make(): the texels' taps on the density's nu grid.
  void make_sun_frame_nu(const std::vector<double>& grid, int mu_s_size);
  SunFrameNode sun_frame_node(double r, double s, double inv_r_i, double mu_i, int phi_size);

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

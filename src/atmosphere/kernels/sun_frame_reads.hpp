// One quadrature node of a texel row of the multiple-scattering pass over
// the density in the sun's frame (sun_frame_density.hpp; the pass is
// multiple_scattering.cpp's): per texel the sun's cosine at the node and
// its mu_s tap (as kernels/node_slice_reads.hpp), the view's azimuth about
// the sun and its cos_phi tap, then the reads: the node's two r texels x
// two mu_s texels x two cos_phi texels of the texel's nu slice, and of a
// second slice for a texel whose nu is clamped between slices. Taps in
// single precision over as many texels as the target has float lanes,
// reads R G B and the pad a lane each; every target does the same IEEE
// operations per lane, so the same bits (tests/atmosphere/kernels_test.cpp
// against sun_frame_tap and sun_frame_read, one texel at a time).
#pragma once

#include "atmosphere/kernels/node_slice_reads.hpp"
#include "atmosphere/kernels/row_blend.hpp"

namespace skybake {

// The node and the row's per-texel constants; the arrays as NodeRow's
// (RowTexels: padded to a multiple of 8, plus 16).
struct SunFrameNode {
  double r = 0, s = 0, inv_r_i = 0;  // the ray's start radius, the node's distance, 1 / its radius
  float mu_i = 0;                    // the view's zenith cosine at the node
  int phi_size = 2;                  // cos_phi texels
  int single = 0;                    // texels [0, single) read one nu slice
  const double* mu_s = nullptr;      // per texel: mu_s and nu of the texel
  const double* nu = nullptr;
  const float* nu_f = nullptr;    // nu and sqrt(1 - nu^2), in float
  const float* sin_nu = nullptr;
  const int* nu_i0 = nullptr;     // the nu slices as m * mu_s_size, and the weight of the second
  const int* nu_i1 = nullptr;
  const float* nu_w = nullptr;
  int *at0 = nullptr, *at1 = nullptr;  // work arrays: each slice's first read
  float *lw = nullptr, *pw = nullptr;  // and the mu_s and cos_phi weights
};

// The taps of texel x, one lane's operations: the first texel read in each
// nu slice (index within an r texel of SunFrameDensity) and the weights of
// the second mu_s and cos_phi texels.
void sun_frame_tap(const SunFrameNode& q, const SunCosineTapsFloat& taps, int x, int& at0,
                   int& at1, float& lw, float& pw);
// The read of texel x with those taps, R G B and the pad: r0 and r1 the
// density's two r texels at the node, rw the second's weight.
Rgb4 sun_frame_read(const SunFrameNode& q, const Rgb4* r0, const Rgb4* r1, float rw, int x);

// For texels [0, end), end a multiple of 8: sum[x] += wS sun_frame_read(x)
// with the taps of sun_frame_tap.
void add_sun_frame_reads(const SunFrameNode& q, const SunCosineTapsFloat& taps, const Rgb4* r0,
                         const Rgb4* r1, float rw, const Rgb4& wS, int end, Rgb4* sum);

}  // namespace skybake

// The blend of four rows of J / sigma_s for each node of the
// multiple-scattering pass (multiple_scattering.cpp; the node's reads are
// kernels/node_slice_reads.hpp's), in single precision over lanes
// (Highway): the same bits on every target.
#pragma once

namespace skybake {

// Four floats: R G B and a zero pad, so a texel is one SSE register.
struct alignas(16) Rgb4 {
  float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

// out = (w0 a + w1 b) + (w2 c + w3 d) over n texels.
void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out);

}  // namespace skybake

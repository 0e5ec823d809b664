// The per-node loops over a texel row of the multiple-scattering pass
// (multiple_scattering.cpp): the blend of four rows of J / sigma_s, the
// texels' sun cosine at the node, and each texel's bilinear read of the
// blend. In single precision, a texel (R, G, B and a zero pad) one SSE
// register; each loop also has an AVX2 twin, two texels or four cosines per
// instruction, used where the CPU has it, with the same bits
// (core/wide_vectors.hpp).
#pragma once

namespace skybake {

// Four floats: R G B and a zero pad, so a texel is one SSE register.
struct alignas(16) Rgb4 {
  float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

// out = w0 a + w1 b + w2 c + w3 d over n texels.
void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out);

// mu_s[x] at distance s along the ray from radius r, at radius r_i:
// clamp_cosine((r mu_s[x] + s nu[x]) inv_r_i), inv_r_i = 1 / r_i, as min /
// max (no branch). A product where a division by r_i was the same within an
// ulp at a third of the divider's work per texel (single scattering's
// SingleScatteringRay::at_suns takes the same product).
void mu_s_at_node(double r, double s, double inv_r_i, const double* mu_s, const double* nu, int n,
                  double* out);

// Per texel x: sum[x] += wS lerp(lerp(s00, s01, lw), lerp(s10, s11, lw), nw),
// s00 = slice[nu_i0[x] + tap_i0[x]], s10 = slice[nu_i1[x] + tap_i0[x]],
// s01 and s11 the next texels along mu_s, lw = float(tap_w[x]), nw = nu_w[x].
struct BilinearTaps {
  const int *nu_i0, *nu_i1, *tap_i0;
  const double* tap_w;
  const float* nu_w;
};
void add_bilinear_row(const Rgb4* slice, const BilinearTaps& taps, const Rgb4& wS, int n,
                      Rgb4* sum);

}  // namespace skybake

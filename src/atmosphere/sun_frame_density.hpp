// The scattering density J_k of one order in the frame of the sun
// (scattering_orders.hpp, "J_k in the sun's frame"): per r texel, nu slice
// and mu_s texel of the 4D table, and the azimuth phi of the view about
// the sun, instead of per (r, mu, mu_s, nu) texel.
//
// A view of cosine nu with the sun, at a point where the sun's zenith
// cosine is mu_s (sun s = (sin_s, 0, mu_s), zenith z):
//   v = nu s + sin_nu (cos_phi e1 + sin_phi e2),
//   e1 = (-mu_s, 0, sin_s) (toward the zenith), e2 = (0, 1, 0),
// so that mu = v . z = nu mu_s + sin_nu sin_s cos_phi. J is even in phi
// (the sky is symmetric about the sun's vertical plane), so the axis is
// cos_phi, from 1 down to -1 in phi_size texels at
//   cos_phi_p = 1 - 2 p / (phi_size - 1)
// (uniform in mu for one (mu_s, nu): J near phi = 0 is a function of
// cos_phi, being even).
//
// Why: along a view ray nu stays the same and mu, mu_s turn together. In
// the 4D table a node of the ray reads J between (mu, mu_s) texels, and
// near the sun J peaks like the Mie phase convolved with itself, along a
// diagonal of (mu, mu_s) that no texel row follows; in this frame the peak
// is along nu, and every node of an unclamped texel's ray reads the texel's
// own nu slice (docs/report.md "The 4D table on a thin slab of dust").
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/kernels/row_blend.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

// Its nu axis: the 4D table's slices, so that the ray of every texel whose
// nu is its slice's reads that slice alone, and between two slices
// kSunFrameNuSteps - 1 more, in equal steps of angle. A texel whose nu is
// clamped between slices (in or near the sun's vertical plane) reads two
// nodes, and J peaks around the sun (Mie's lobe convolved with itself)
// far narrower than the slices' 44 degrees there (Mars, worst channel
// against the path tracer: 3.4 % with the slices alone, 2.7 % with three
// more nodes near the sun, 2.2 % with 2 steps, 2.1 % with 4 at 1.5x the
// density's cost).
constexpr int kSunFrameNuSteps = 2;
std::vector<double> sun_frame_nu_grid(int nu_size);

struct SunFrameDensity {
  ScatteringShape shape;
  int phi_size = 0;
  std::vector<double> nu;  // sun_frame_nu_grid, ascending
  // J / sigma_s (RGB, pad 0) at texel (z, m, l, p): r texel z, nu m,
  // mu_s texel l, cos_phi texel p (index()).
  std::vector<Rgb4> texels;

  int nu_count() const { return int(nu.size()); }
  size_t index(int z, int m, int l, int p) const {
    return ((size_t(z) * nu.size() + m) * shape.mu_s_size + l) * phi_size + p;
  }
  // Texels of one r texel.
  size_t r_stride() const { return nu.size() * shape.mu_s_size * phi_size; }
};

// The tap of cosine nu on the grid: nodes i0, i1 = i0 + 1 (or i0 at the
// top) and the weight of i1; 0 on a node.
AxisTap sun_frame_nu_tap(const std::vector<double>& grid, double nu);

// The cos_phi texels of a density for the 4D table of `shape`: a quarter
// of its mu texels (which span both halves of [-1, 1]), at least 8.
inline int sun_frame_azimuths(const ScatteringShape& shape) {
  return shape.mu_size / 4 > 8 ? shape.mu_size / 4 : 8;
}

// cos_phi of texel p.
inline double sun_frame_cos_phi(int p, int phi_size) {
  return 1.0 - 2.0 * p / double(phi_size - 1);
}

// The view of (mu_s, nu, cos_phi) in the density's frame (the sun in the
// xz plane, x >= 0; the header's formula), y >= 0.
glm::dvec3 sun_frame_view(double mu_s, double nu, double cos_phi);

// cos_phi of the view of zenith cosine mu at (mu_s, nu), clamped to
// [-1, 1]; 1 where the azimuth is undefined (sun or view along the
// zenith, or the view along the sun: J does not depend on it there).
double sun_frame_cos_phi_of(double mu, double mu_s, double nu);

// J / sigma_s at (r texel tap, mu, mu_s, nu): the r and mu_s taps of the
// 4D table's axes, nu between slices, cos_phi between texels; in double,
// the reference for the multiple-scattering pass's reads.
glm::dvec3 lookup_sun_frame_density(const SunFrameDensity& J, const MuSAxis& mu_s_axis,
                                    const AxisTap& r_tap, double mu, double mu_s, double nu);

}  // namespace skybake

// Direction rules for integrals over the unit sphere (the multiple-scattering
// integral of Hillaire 2020 eq. 5-8): unit vectors with weights, each weight
// the fraction of 4 pi its direction stands for (the weights sum to 1, so a
// weighted sum of f is the mean of f over the sphere, i.e. the integral times
// 1 / (4 pi)). docs/reference.md "Multiple scattering (Hillaire)".
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace skybake {

struct SphereRule {
  std::vector<glm::dvec3> dirs;
  std::vector<double> weights;  // empty: every direction weighs 1 / dirs.size()
};

// Gauss-Legendre nodes and weights on [-1, 1] (n >= 1; Newton on P_n from
// the Chebyshev guess, converged to ~1e-15; weights sum to 2).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// A product rule for an integrand symmetric about the x-z plane (f(x, y, z) =
// f(x, -y, z)): the zenith cosine z split at `z_split` in (-1, 1), with
// `below` Gauss-Legendre nodes on [-1, z_split] and `above` on [z_split, 1],
// times `azimuths` midpoint azimuths on the half circle phi in (0, pi) (y > 0),
// each standing for itself and its mirror image, so the rule is the midpoint
// rule with 2 `azimuths` points on the whole circle at the cost of
// `azimuths`. Directions: (sqrt(1 - z^2) cos phi, sqrt(1 - z^2) sin phi, z).
// Exact for polynomials in z of degree < 2 min(below, above) on each piece
// times trigonometric polynomials in phi of degree < 2 `azimuths`.
SphereRule symmetric_gauss_rule(int below, int above, int azimuths, double z_split);

// How symmetric_gauss_rule spends a budget of `rays` (>= 1) directions:
// azimuths = max(1, round(sqrt(rays / 8))), zenith nodes n = rays / azimuths
// (rounded down, at least 2), below = max(1, round(n / 5)) under the split and the rest
// above it (at least 1), so the rule casts at most max(rays, 2) rays. Most nodes go
// above the split: near the terminator the lit air a point sees lies just
// above its horizon (docs/reference.md "Multiple scattering (Hillaire)").
struct SymmetricGaussShape {
  int below, above, azimuths;
};
SymmetricGaussShape symmetric_gauss_shape(int rays);

}  // namespace skybake

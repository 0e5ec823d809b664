// The view-dependent multiple-scattering source (docs/reference.md
// "Psi_ms by view"): the source of orders >= 2 toward a view at a point,
// per unit of sigma_s E, as
//   Psi(r, mu_s, nu, mu_v) = a(r, mu_s, nu) + b(r, mu_s, mu_v),
// nu the cosine between the view ray and the sun, mu_v the view ray's
// zenith cosine at the point. Each term is held at nodes of its cosine and
// read linearly between the two nearest. Why this form: with a phase of
// forward peak (g = 0.85 dust) the source toward a viewer is close to the
// light arriving from straight behind the point; that light is the
// aureole around the sun, a function of nu, plus the diffuse sky, which
// brightens toward the horizon, mostly a function of mu_v. Along a straight
// ray under a directional sun nu does not change, so a march finds its nu
// pair once; mu_v changes from step to step.
//
// Axes, nodes at x_k = k / (nodes - 1):
//   nu:   x = (0.5 - 0.5 nu)^(1/4), inverse nu = 1 - 2 x^4: the quarter power
//         crowds the nodes toward the sun (2.3, 9.4, 21 degrees off it at 8);
//   mu_v: x = 0.5 + 0.5 sign(mu_v) sqrt(|mu_v|), inverse
//         mu_v = sign(x - 0.5) (2 x - 1)^2: crowded at the horizontal.
//
// The nodes' values are fitted by weighted least squares to the source seen
// along a sphere grid's directions (fit_view_nodes); what the source does
// beyond a sum of the two (the diffuse sky's azimuth, the aureole's
// zenith) this form cannot hold.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace skybake {

// The axis pairs (see the opening comment); cosines clamped to [-1, 1].
double nu_node_unit_from_cosine(double nu);
double nu_node_cosine_from_unit(double x);
double zenith_node_unit_from_cosine(double mu_v);
double zenith_node_cosine_from_unit(double x);

// The two nodes a unit coordinate x in [0, 1] falls between on an axis of
// `nodes` nodes: `first` and first + 1, weight `f` on the second.
struct NodePair {
  int first = 0;
  double f = 0.0;
};
NodePair node_pair(int nodes, double x);

struct PsiViewShape {
  int nu_nodes = 8;      // >= 2
  int zenith_nodes = 0;  // 0 (no mu_v term) or >= 2
  int size() const { return nu_nodes + zenith_nodes; }
};

// The nodes' values per channel (nu nodes first, then mu_v nodes),
// minimising
//   sum_v w_v (a(nu_v) + b(mu_v) - j_v)^2
//     + s (sum_k (a_{k-1} - 2 a_k + a_{k+1})^2 + sum_m (b_{m-1} - 2 b_m + b_{m+1})^2)
//     + e (sum_k (a_k - anchor)^2 + sum_m b_m^2),
// s = kViewNodeSmoothing and e = kViewNodeRidge times (sum_v w_v) /
// shape.size(). The curvature term decides the nodes few directions reach
// (those nearest the sun, where a sphere grid's cells are wider than the
// nodes' spacing) by extending their neighbours' slope; the ridge, far
// weaker, splits the constant the two terms share (toward the isotropic
// value `anchor` for a, 0 for b). nu, mu_v, j, w: one entry per direction.
constexpr double kViewNodeSmoothing = 1e-3;
constexpr double kViewNodeRidge = 1e-7;
std::vector<glm::dvec3> fit_view_nodes(const std::vector<double>& nu,
                                       const std::vector<double>& mu_v,
                                       const std::vector<glm::dvec3>& j,
                                       const std::vector<glm::dvec3>& w, glm::dvec3 anchor,
                                       PsiViewShape shape);

// a(nu) + b(mu_v) from the nodes fit_view_nodes returns (one channel each).
glm::dvec3 evaluate_view_nodes(const std::vector<glm::dvec3>& nodes, PsiViewShape shape,
                               double nu, double mu_v);

}  // namespace skybake

// Energy-conserving ray quadrature; see the header.
#include "atmosphere/ray_transfer.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

namespace {

// int_{-1}^{x_i} l_j(t) dt for the Lagrange basis l_j through the Gauss
// nodes (-a, 0, a), a = sqrt(3/5), at each node x_i: the optical depth from
// a segment's start to its node i is half * sum_j kPartial[i][j] sigma_j.
struct PartialWeights {
  double w[3][3];
  PartialWeights() {
    const double a = kGauss3Nodes[2], a2 = a * a;
    auto F = [&](int j, double x) {
      const double x2 = x * x, x3 = x2 * x;
      switch (j) {
        case 0:  // t (t - a) / (2 a^2)
          return (x3 / 3.0 - a * x2 / 2.0 - (-1.0 / 3.0 - a / 2.0)) / (2.0 * a2);
        case 1:  // 1 - t^2 / a^2
          return x - x3 / (3.0 * a2) - (-1.0 + 1.0 / (3.0 * a2));
        default:  // t (t + a) / (2 a^2)
          return (x3 / 3.0 + a * x2 / 2.0 - (-1.0 / 3.0 + a / 2.0)) / (2.0 * a2);
      }
    };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) w[i][j] = F(j, kGauss3Nodes[i]);
  }
};

const PartialWeights kPartial;

// Fills the nodes' s, r and sigma_t; returns the segments.
void place_nodes(const Atmosphere& atm, double r, double mu, double d, int nodes,
                 std::vector<RaySegment>& segments, std::vector<TransferNode>& out) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  ray_segments(r, mu, d, nodes, segments);
  out.resize(3 * segments.size());
  for (size_t k = 0; k < segments.size(); ++k) {
    const double mid = 0.5 * (segments[k].a + segments[k].b);
    const double half = 0.5 * (segments[k].b - segments[k].a);
    for (int i = 0; i < 3; ++i) {
      TransferNode& n = out[3 * k + i];
      n.s = mid + half * kGauss3Nodes[i];
      n.r = std::clamp(radius_after(r, mu, n.s), rb, rt);
      n.sigma_t = extinction_at(atm, n.r - rb);
    }
  }
}

}  // namespace

void ray_transfer(const Atmosphere& atm, double r, double mu, double d, int nodes,
                  RayTransfer& out) {
  std::vector<RaySegment> segments;
  place_nodes(atm, r, mu, d, nodes, segments, out.nodes);
  glm::dvec3 depth(0.0);  // optical depth from the origin to the segment's start
  for (size_t k = 0; k < segments.size(); ++k) {
    const double half = 0.5 * (segments[k].b - segments[k].a);
    TransferNode* n = &out.nodes[3 * k];
    for (int c = 0; c < 3; ++c) {
      const double sigma[3] = {n[0].sigma_t[c], n[1].sigma_t[c], n[2].sigma_t[c]};
      const double tau = half * (kGauss3Weights[0] * sigma[0] + kGauss3Weights[1] * sigma[1] +
                                 kGauss3Weights[2] * sigma[2]);
      double raw = 0.0, partial_before = 0.0, T[3];
      for (int i = 0; i < 3; ++i) {
        double partial = half * (kPartial.w[i][0] * sigma[0] + kPartial.w[i][1] * sigma[1] +
                                 kPartial.w[i][2] * sigma[2]);
        // The quadratic may dip below zero between steep nodes: keep the
        // depth monotone and within the segment's.
        partial = std::clamp(partial, partial_before, tau);
        partial_before = partial;
        T[i] = std::exp(-(depth[c] + partial));
        raw += half * kGauss3Weights[i] * sigma[i] * T[i];
      }
      // T(0, a) (1 - exp(-tau)), the exact in-scattering weight of the segment.
      const double exact = -std::exp(-depth[c]) * std::expm1(-tau);
      const double scale = raw > 0.0 ? exact / raw : 1.0;
      for (int i = 0; i < 3; ++i) n[i].weight[c] = half * kGauss3Weights[i] * T[i] * scale;
      depth[c] += tau;
    }
  }
  out.optical_depth = depth;
  out.transmittance = glm::exp(-depth);
}

glm::dvec3 ray_transmittance(const Atmosphere& atm, double r, double mu, double d, int nodes) {
  std::vector<RaySegment> segments;
  std::vector<TransferNode> placed;
  place_nodes(atm, r, mu, d, nodes, segments, placed);
  glm::dvec3 depth(0.0);
  for (size_t k = 0; k < segments.size(); ++k) {
    const double half = 0.5 * (segments[k].b - segments[k].a);
    for (int i = 0; i < 3; ++i) depth += half * kGauss3Weights[i] * placed[3 * k + i].sigma_t;
  }
  return glm::exp(-depth);
}

}  // namespace skybake

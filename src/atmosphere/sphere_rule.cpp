#include "atmosphere/sphere_rule.hpp"

#include <algorithm>
#include <cmath>

#include "core/math.hpp"

namespace skybake {

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(size_t(n), 0.0);
  weights.assign(size_t(n), 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      // P_n(x) and P_n'(x) by the three-term recurrence.
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? x : p1;
      const double pm = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pm) / (x * x - 1.0);
      const double step = pn / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    // Recompute P_n' at the converged node for the weight 2 / ((1 - x^2) P_n'^2).
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n == 1 ? 1.0 : n * (x * p1 - p0) / (x * x - 1.0);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    nodes[size_t(i)] = -x;
    nodes[size_t(n - 1 - i)] = x;
    weights[size_t(i)] = w;
    weights[size_t(n - 1 - i)] = w;
  }
  if (n % 2 == 1) nodes[size_t(n / 2)] = 0.0;
}

SphereRule symmetric_gauss_rule(int below, int above, int azimuths, double z_split) {
  SphereRule rule;
  std::vector<double> zs, wz;
  const auto add_piece = [&](int n, double lo, double hi) {
    if (n < 1) return;
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    for (int i = 0; i < n; ++i) {
      zs.push_back(0.5 * (lo + hi) + 0.5 * (hi - lo) * x[size_t(i)]);
      // dOmega / (4 pi) = dz dphi / (4 pi); the half circle with its mirror
      // is 2 pi, so each z node carries w (hi - lo) / 2 / 2.
      wz.push_back(0.25 * (hi - lo) * w[size_t(i)]);
    }
  };
  add_piece(below, -1.0, z_split);
  add_piece(above, z_split, 1.0);
  for (size_t i = 0; i < zs.size(); ++i) {
    const double s = safe_sqrt(1.0 - zs[i] * zs[i]);
    for (int j = 0; j < azimuths; ++j) {
      const double phi = kPi * (j + 0.5) / azimuths;
      rule.dirs.push_back({s * std::cos(phi), s * std::sin(phi), zs[i]});
      rule.weights.push_back(wz[i] / azimuths);
    }
  }
  return rule;
}

SymmetricGaussShape symmetric_gauss_shape(int rays) {
  rays = std::max(rays, 1);
  const int azimuths = std::max(1, int(std::lround(std::sqrt(rays / 8.0))));
  const int zenith = std::max(2, rays / azimuths);
  const int below = std::max(1, int(std::lround(zenith / 5.0)));
  return {below, std::max(1, zenith - below), azimuths};
}

}  // namespace skybake

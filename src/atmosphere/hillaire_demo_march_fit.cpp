#include "atmosphere/hillaire_demo_march_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "atmosphere/hillaire_demo_march.hpp"
#include "core/math.hpp"
#include "core/metadata.hpp"

namespace skybake {

namespace {

struct DemoFitView {
  glm::dvec3 position, dir, sun;
};

// Training views (docs/decisions/hillaire-demo-march.md): away from the
// report's views, which judge the fit.
std::vector<DemoFitView> demo_fit_views(const Atmosphere& atm) {
  std::vector<DemoFitView> out;
  for (double alt : {1.0, 300.0, 1e3, 3e3, 10e3})
    for (double sun_deg : {80.0, 45.0, 20.0, 6.0, 3.0, 1.0})
      for (double e_deg : {1.0, 4.0, 7.0, 15.0, 30.0, 40.0, 60.0, 70.0, 89.0})
        for (double az : {0.2, 1.1, 1.9, 2.9}) {
          const double e = e_deg * kDeg, s = sun_deg * kDeg;
          out.push_back({{0.0, 0.0, atm.bottom_radius_m + alt},
                         {std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)},
                         {std::cos(s), 0.0, std::sin(s)}});
        }
  return out;
}

double demo_fit_hat(double x, int node) { return std::max(0.0, 1.0 - std::abs(x - node)); }

// Node coordinate of a row of a table in his layout (sub-uv positions).
double demo_fit_row_node(int row, int rows) {
  const double n = rows;
  const double x = std::clamp(((row + 0.5) * (n + 1.0) / n - 0.5) / n, 0.0, 1.0);
  return x * (kDemoMarchFitNodes - 1);
}

// The table with each row scaled by w(row).
template <typename Weight>
Texture demo_fit_scaled(const Texture& ms, Weight w) {
  Texture out = ms;
  for (int j = 0; j < ms.height; ++j) {
    const glm::dvec3 f = w(j);
    for (int i = 0; i < ms.width; ++i)
      for (int c = 0; c < 3; ++c) out.at(i, j, 0, 0, c) = float(ms.at(i, j, 0, 0, c) * f[c]);
  }
  return out;
}

// Per view: the march with Psi_ms = 0 (what k does not scale) and with
// each node's hat alone (less the former); the march is linear in Psi_ms.
struct DemoFitRows {
  std::vector<glm::dvec3> fixed;
  std::vector<std::array<glm::dvec3, kDemoMarchFitNodes>> basis;
};

DemoFitRows demo_fit_rows(const Atmosphere& atm, const Texture& t, const Texture& ms,
                          const std::vector<DemoFitView>& views, const DemoMarch& march) {
  std::vector<Texture> hats;
  for (int b = 0; b < kDemoMarchFitNodes; ++b)
    hats.push_back(demo_fit_scaled(
        ms, [&](int j) { return glm::dvec3(demo_fit_hat(demo_fit_row_node(j, ms.height), b)); }));
  DemoFitRows rows;
  rows.fixed.resize(views.size());
  rows.basis.resize(views.size());
  tbb::parallel_for(size_t(0), views.size(), [&](size_t v) {
    const DemoFitView& g = views[v];
    rows.fixed[v] = demo_integrate(atm, {&t, nullptr}, g.position, g.dir, g.sun, march).luminance;
    for (int b = 0; b < kDemoMarchFitNodes; ++b)
      rows.basis[v][b] = demo_integrate(atm, {&t, &hats[b]}, g.position, g.dir, g.sun, march)
                             .luminance -
                         rows.fixed[v];
  });
  return rows;
}

// Solves the normal equations A k = b (symmetric positive definite).
std::array<double, kDemoMarchFitNodes> demo_fit_solve(std::vector<double> a, std::vector<double> b) {
  const int n = kDemoMarchFitNodes;
  for (int p = 0; p < n; ++p)
    for (int r = p + 1; r < n; ++r) {
      const double f = a[r * n + p] / a[p * n + p];
      for (int c = p; c < n; ++c) a[r * n + c] -= f * a[p * n + c];
      b[r] -= f * b[p];
    }
  std::array<double, kDemoMarchFitNodes> x{};
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int c = r + 1; c < n; ++c) s -= a[r * n + c] * x[c];
    x[r] = s / a[r * n + r];
  }
  return x;
}

}  // namespace

DemoMarchFit fit_demo_march(const Atmosphere& atm, const Texture& transmittance_demo,
                            const Texture& multiscattering_demo) {
  const std::vector<DemoFitView> views = demo_fit_views(atm);
  DemoMarch converged, low, high;
  converged.min_samples = converged.max_samples = 2000.0;
  low.min_samples = 4.0;
  low.max_samples = 14.0;
  high.min_samples = 30.0;
  high.max_samples = 31.0;
  std::vector<glm::dvec3> target(views.size());
  tbb::parallel_for(size_t(0), views.size(), [&](size_t v) {
    const DemoFitView& g = views[v];
    target[v] = demo_integrate(atm, {&transmittance_demo, &multiscattering_demo}, g.position,
                               g.dir, g.sun, converged)
                    .luminance;
  });
  const DemoFitRows settings[2] = {
      demo_fit_rows(atm, transmittance_demo, multiscattering_demo, views, low),
      demo_fit_rows(atm, transmittance_demo, multiscattering_demo, views, high)};
  // Minimises sum ((fixed + sum_b k_b basis_b - target) / target)^2 over
  // both settings' views, plus a small pull toward k = 1 for nodes no
  // sample reaches.
  const int n = kDemoMarchFitNodes;
  const double lambda = 1e-4 * 2.0 * double(views.size());
  DemoMarchFit fit;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> a(n * n, 0.0), b(n, lambda);
    for (int i = 0; i < n; ++i) a[i * n + i] = lambda;
    for (const DemoFitRows& rows : settings)
      for (size_t v = 0; v < views.size(); ++v) {
        const double y = target[v][c], rhs = y - rows.fixed[v][c];
        if (!(y > 0.0)) continue;
        for (int i = 0; i < n; ++i) {
          b[i] += rows.basis[v][i][c] * rhs / (y * y);
          for (int j = 0; j < n; ++j)
            a[i * n + j] += rows.basis[v][i][c] * rows.basis[v][j][c] / (y * y);
        }
      }
    const std::array<double, kDemoMarchFitNodes> k = demo_fit_solve(a, b);
    for (int i = 0; i < n; ++i) fit.factors[i][c] = k[i];
  }
  return fit;
}

glm::dvec3 demo_march_factor(const Atmosphere& atm, const DemoMarchFit& fit, double altitude_m) {
  const double shell = atm.top_radius_m - atm.bottom_radius_m;
  const double x = std::clamp(altitude_m / shell, 0.0, 1.0) * (kDemoMarchFitNodes - 1);
  glm::dvec3 k(0.0);
  for (int b = 0; b < kDemoMarchFitNodes; ++b) k += fit.factors[b] * demo_fit_hat(x, b);
  return k;
}

void apply_demo_march_fit(const Atmosphere& atm, const DemoMarchFit& fit,
                          Texture& multiscattering_demo) {
  const double shell = atm.top_radius_m - atm.bottom_radius_m;
  const int rows = multiscattering_demo.height;
  multiscattering_demo = demo_fit_scaled(multiscattering_demo, [&](int j) {
    return demo_march_factor(atm, fit, demo_fit_row_node(j, rows) / (kDemoMarchFitNodes - 1) * shell);
  });
  set_meta(multiscattering_demo.metadata, "demo_march_fit", kDemoMarchFitNodes);
  for (int i = 0; i < kDemoMarchFitNodes; ++i)
    set_meta(multiscattering_demo.metadata, "demo_march_fit." + std::to_string(i), fit.factors[i]);
}

}  // namespace skybake

// See the header and docs/reference.md "Psi_ms by view".
#include "atmosphere/psi_view_nodes.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace skybake {

double nu_node_unit_from_cosine(double nu) {
  return std::sqrt(std::sqrt(std::clamp(0.5 - 0.5 * nu, 0.0, 1.0)));
}

double nu_node_cosine_from_unit(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return 1.0 - 2.0 * (x * x) * (x * x);
}

double zenith_node_unit_from_cosine(double mu_v) {
  mu_v = std::clamp(mu_v, -1.0, 1.0);
  const double s = std::sqrt(std::abs(mu_v));
  return 0.5 + 0.5 * (mu_v < 0.0 ? -s : s);
}

double zenith_node_cosine_from_unit(double x) {
  const double y = 2.0 * std::clamp(x, 0.0, 1.0) - 1.0;
  return y < 0.0 ? -y * y : y * y;
}

NodePair node_pair(int nodes, double x) {
  const double s = std::clamp(x, 0.0, 1.0) * double(nodes - 1);
  const int first = std::min(int(s), nodes - 2);
  return {first, s - double(first)};
}

namespace {

// Solves the symmetric positive definite system m x = b (n x n, row-major)
// in place by Cholesky's factorisation; b receives x.
void solve_view_node_system(std::vector<double>& m, std::vector<double>& b, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    double d = m[k * n + k];
    for (size_t p = 0; p < k; ++p) d -= m[k * n + p] * m[k * n + p];
    d = std::sqrt(std::max(d, 1e-300));
    m[k * n + k] = d;
    for (size_t i = k + 1; i < n; ++i) {
      double s = m[i * n + k];
      for (size_t p = 0; p < k; ++p) s -= m[i * n + p] * m[k * n + p];
      m[i * n + k] = s / d;
    }
  }
  for (size_t i = 0; i < n; ++i) {  // L y = b
    for (size_t p = 0; p < i; ++p) b[i] -= m[i * n + p] * b[p];
    b[i] /= m[i * n + i];
  }
  for (size_t i = n; i-- > 0;) {  // L^T x = y
    for (size_t p = i + 1; p < n; ++p) b[i] -= m[p * n + i] * b[p];
    b[i] /= m[i * n + i];
  }
}

// lambda sum_k (c_{k-1} - 2 c_k + c_{k+1})^2 over the `count` nodes from
// `first`, added to the normal matrix m (n x n).
void add_view_node_curvature(std::vector<double>& m, size_t first, size_t count, size_t n,
                             double lambda) {
  for (size_t k = 1; k + 1 < count; ++k) {
    const size_t i[3] = {first + k - 1, first + k, first + k + 1};
    const double d[3] = {1.0, -2.0, 1.0};
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) m[i[p] * n + i[q]] += lambda * d[p] * d[q];
  }
}

// The (up to) four basis functions a direction touches: index and weight.
struct ViewNodeTaps {
  size_t index[4];
  double weight[4];
  int count;
};
ViewNodeTaps view_node_taps(PsiViewShape shape, double nu, double mu_v) {
  ViewNodeTaps t{};
  const NodePair a = node_pair(shape.nu_nodes, nu_node_unit_from_cosine(nu));
  t.index[0] = size_t(a.first), t.weight[0] = 1.0 - a.f;
  t.index[1] = size_t(a.first + 1), t.weight[1] = a.f;
  t.count = 2;
  if (shape.zenith_nodes > 0) {
    const NodePair b = node_pair(shape.zenith_nodes, zenith_node_unit_from_cosine(mu_v));
    const size_t base = size_t(shape.nu_nodes);
    t.index[2] = base + size_t(b.first), t.weight[2] = 1.0 - b.f;
    t.index[3] = base + size_t(b.first + 1), t.weight[3] = b.f;
    t.count = 4;
  }
  return t;
}

}  // namespace

std::vector<glm::dvec3> fit_view_nodes(const std::vector<double>& nu,
                                       const std::vector<double>& mu_v,
                                       const std::vector<glm::dvec3>& j,
                                       const std::vector<glm::dvec3>& w, glm::dvec3 anchor,
                                       PsiViewShape shape) {
  if (shape.nu_nodes < 2 || shape.zenith_nodes == 1 || nu.size() != j.size() ||
      nu.size() != w.size() || nu.size() != mu_v.size())
    throw Error("fit_view_nodes: expected at least 2 nu nodes, 0 or at least 2 zenith nodes "
                "and one cosine, source and weight per direction");
  const size_t n = size_t(shape.size());
  std::vector<ViewNodeTaps> taps(nu.size());
  for (size_t v = 0; v < nu.size(); ++v) taps[v] = view_node_taps(shape, nu[v], mu_v[v]);
  std::vector<glm::dvec3> out(n, glm::dvec3(0.0));
  for (int c = 0; c < 3; ++c) {
    std::vector<double> m(n * n, 0.0), b(n, 0.0);
    double total = 0.0;
    for (size_t v = 0; v < nu.size(); ++v) {
      const ViewNodeTaps& t = taps[v];
      const double wv = w[v][c];
      for (int p = 0; p < t.count; ++p) {
        b[t.index[p]] += wv * t.weight[p] * j[v][c];
        for (int q = 0; q < t.count; ++q)
          m[t.index[p] * n + t.index[q]] += wv * t.weight[p] * t.weight[q];
      }
      total += wv;
    }
    const double scale = total > 0.0 ? total / double(n) : 1.0;
    add_view_node_curvature(m, 0, size_t(shape.nu_nodes), n, kViewNodeSmoothing * scale);
    add_view_node_curvature(m, size_t(shape.nu_nodes), size_t(shape.zenith_nodes), n,
                            kViewNodeSmoothing * scale);
    for (size_t k = 0; k < n; ++k) {
      m[k * n + k] += kViewNodeRidge * scale;
      if (k < size_t(shape.nu_nodes)) b[k] += kViewNodeRidge * scale * anchor[c];
    }
    solve_view_node_system(m, b, n);
    for (size_t k = 0; k < n; ++k) out[k][c] = b[k];
  }
  return out;
}

glm::dvec3 evaluate_view_nodes(const std::vector<glm::dvec3>& nodes, PsiViewShape shape,
                               double nu, double mu_v) {
  const ViewNodeTaps t = view_node_taps(shape, nu, mu_v);
  glm::dvec3 sum(0.0);
  for (int p = 0; p < t.count; ++p) sum += t.weight[p] * nodes[t.index[p]];
  return sum;
}

}  // namespace skybake

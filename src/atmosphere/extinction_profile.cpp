#include "atmosphere/extinction_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/density_kinks.hpp"
#include "core/kernels/exp_block.hpp"

namespace skybake {

bool integrated_by_quadrature(const MediumComponent& c, bool closed_form_linear) {
  if (c.scattering_per_m + c.absorption_per_m == glm::dvec3(0.0)) return false;
  return !(closed_form_linear && !c.density.layers.empty() && is_piecewise_linear(c.density));
}

namespace {

// density[j] of one layer's formula at h[j], clamped to [0, 1]
// (medium.cpp density_at). With NodeExp::block the exponentials are taken
// in one vectorized pass, density[] holding their arguments first.
void one_layer_densities(const DensityLayer& l, const double* h, double* density, size_t n,
                         NodeExp exp_kind) {
  if (l.exp_term == 0.0) {
    for (size_t j = 0; j < n; ++j)
      density[j] = std::min(std::max(l.linear_term_per_m * h[j] + l.constant_term, 0.0), 1.0);
    return;
  }
  if (exp_kind == NodeExp::block) {
    for (size_t j = 0; j < n; ++j) density[j] = l.exp_scale_per_m * h[j];
    exp_block(density, n);
    for (size_t j = 0; j < n; ++j) {
      const double e = l.exp_term * density[j];
      density[j] =
          std::min(std::max(e + l.linear_term_per_m * h[j] + l.constant_term, 0.0), 1.0);
    }
    return;
  }
  for (size_t j = 0; j < n; ++j) {
    const double e = l.exp_term * std::exp(l.exp_scale_per_m * h[j]);
    density[j] =
        std::min(std::max(e + l.linear_term_per_m * h[j] + l.constant_term, 0.0), 1.0);
  }
}

// Two doubles of one vector: lane 0 the even nodes' chain of additions,
// lane 1 the odd nodes', the same IEEE operations as two scalar sums.
typedef double v2d __attribute__((vector_size(16)));
typedef double v2d_any __attribute__((vector_size(16), aligned(8), may_alias));  // any double

// sum_j w[j] e[j] in two partial sums, even and odd j, added at the end (a
// chain half as long as one sum's).
double weighted_sum(const double* w, const double* e, size_t n) {
  v2d sums = {0.0, 0.0};
  size_t j = 0;
  for (; j + 1 < n; j += 2)
    sums += *reinterpret_cast<const v2d_any*>(w + j) * *reinterpret_cast<const v2d_any*>(e + j);
  if (j < n) sums[0] += w[j] * e[j];
  return sums[0] + sums[1];
}

// a exp(b h) with 0 < a <= 1, b <= 0 and nothing else stays in (0, 1] at
// h >= 0: the clamp cannot act (nodes a rounding below the ground read
// 1 + 1e-13 at most).
bool unclamped_exponential(const DensityProfile& p) {
  if (p.layers.size() != 1) return false;
  const DensityLayer& l = p.layers[0];
  return l.linear_term_per_m == 0.0 && l.constant_term == 0.0 && l.exp_term > 0.0 &&
         l.exp_term <= 1.0 && l.exp_scale_per_m <= 0.0;
}

}  // namespace

ExtinctionProfile::ExtinctionProfile(const Atmosphere& atm, bool closed_form_linear,
                                     NodeExp exp_kind) {
  for (const MediumComponent& c : atm.components) {
    // A component without extinction adds d * 0 = +0 to a sum that starts
    // at +0, so leaving it out changes no bit.
    if (!integrated_by_quadrature(c, closed_form_linear) || c.density.layers.empty()) continue;
    const glm::dvec3 sigma_t = c.scattering_per_m + c.absorption_per_m;
    Component out{sigma_t, layers_.size(), c.density.layers.size(), NodeExp::libm, false};
    // exp_block needs |b h| <= 708 at every altitude in [0, top_h] (a
    // margin for nodes a rounding above the top); else this component keeps std::exp.
    const double top_h = atm.top_radius_m - atm.bottom_radius_m;
    bool block_safe = exp_kind == NodeExp::block;
    for (const DensityLayer& l : c.density.layers)
      block_safe = block_safe && std::abs(l.exp_scale_per_m) * top_h <= 700.0;
    out.exp_kind = block_safe ? NodeExp::block : NodeExp::libm;
    out.unclamped_exponential = block_safe && unclamped_exponential(c.density);
    double layer_bottom = 0.0;
    for (size_t i = 0; i < c.density.layers.size(); ++i) {
      const DensityLayer& l = c.density.layers[i];
      const bool last = i + 1 == c.density.layers.size();
      const double inf = std::numeric_limits<double>::infinity();
      layers_.push_back({last ? inf : layer_bottom + l.width_m, l});
      layer_bottom += l.width_m;
    }
    if (out.unclamped_exponential) ++unclamped_count_;
    components_.push_back(out);
  }
}

glm::dvec3 ExtinctionProfile::integrate(const std::vector<double>& h, const std::vector<double>& w,
                                        std::vector<double>& density) const {
  glm::dvec3 tau(0.0);
  const size_t n = h.size();
  // The unclamped exponentials' exps in one block: exp(b h[j]) of the k-th
  // such component at density[k n + j]; the other components' densities
  // after them, one component at a time.
  density.resize(n * (unclamped_count_ + 1));
  size_t unclamped = 0;
  for (const Component& c : components_) {
    if (!c.unclamped_exponential) continue;
    const double b = layers_[c.first_layer].layer.exp_scale_per_m;
    double* e = &density[n * unclamped++];
    for (size_t j = 0; j < n; ++j) e[j] = b * h[j];
  }
  if (unclamped > 0) exp_block(density.data(), n * unclamped);
  unclamped = 0;
  for (const Component& c : components_) {
    const Layer* first = &layers_[c.first_layer];
    if (c.unclamped_exponential) {
      const double sum = weighted_sum(w.data(), &density[n * unclamped++], n);
      tau += (first->layer.exp_term * sum) * c.sigma_t;
      continue;
    }
    double* density_of_c = &density[n * unclamped_count_];
    if (c.layer_count == 1) {
      one_layer_densities(first->layer, h.data(), density_of_c, n, c.exp_kind);
    } else {
      const Layer* last = first + (c.layer_count - 1);
      for (size_t j = 0; j < n; ++j) {
        const Layer* layer = first;
        while (layer != last && !(h[j] < layer->top)) ++layer;
        one_layer_densities(layer->layer, &h[j], &density_of_c[j], 1, c.exp_kind);
      }
    }
    double sum = 0.0;
    for (size_t j = 0; j < n; ++j) sum += w[j] * density_of_c[j];
    tau += sum * c.sigma_t;
  }
  return tau;
}

}  // namespace skybake

#include "atmosphere/medium_block.hpp"

#include <algorithm>
#include <cmath>

#include "core/kernels/exp_block.hpp"
#include "core/scratch.hpp"

namespace skybake {

void density_block(const DensityProfile& profile, const double* h, size_t n, NodeExp exp_kind,
                   MediumBlock& scratch, double* density) {
  if (profile.layers.empty()) {
    std::fill(density, density + n, 0.0);
    return;
  }
  // A profile of linear layers only (ozone's tent): layer_density ignores
  // the exponential where exp_term is 0, so none is taken.
  const bool linear = std::all_of(profile.layers.begin(), profile.layers.end(),
                                  [](const DensityLayer& l) { return l.exp_term == 0.0; });
  if (linear) {
    for (size_t i = 0; i < n; ++i) density[i] = layer_density(layer_at(profile, h[i]), h[i], 0.0);
    return;
  }
  // One layer (the exponential profiles): no layer to look up per altitude,
  // and loops the compiler vectorizes, with the layer copied to a local (the
  // output's doubles could alias the profile's: its terms would be reloaded
  // at every altitude).
  const DensityLayer* only = profile.layers.size() == 1 ? &profile.layers[0] : nullptr;
  double* exponent = scratch_entries(scratch.exponent, n);
  // exp_block's range (NodeExp::block): clamped as written, not in a pass of its own.
  const double bound = exp_kind == NodeExp::block ? 708.0 : INFINITY;
  const auto clamped = [bound](double x) { return std::min(std::max(x, -bound), bound); };
  if (only) {
    const double scale = only->exp_scale_per_m;
    for (size_t i = 0; i < n; ++i) exponent[i] = clamped(scale * h[i]);
  } else {
    scratch_entries(scratch.layer, n);
    for (size_t i = 0; i < n; ++i) {
      scratch.layer[i] = &layer_at(profile, h[i]);
      exponent[i] = clamped(scratch.layer[i]->exp_scale_per_m * h[i]);
    }
  }
  if (exp_kind == NodeExp::block) {
    exp_block(exponent, n);
  } else {
    for (size_t i = 0; i < n; ++i) exponent[i] = std::exp(exponent[i]);
  }
  if (only) {
    const DensityLayer layer = *only;
    for (size_t i = 0; i < n; ++i) density[i] = layer_density(layer, h[i], exponent[i]);
    return;
  }
  for (size_t i = 0; i < n; ++i) density[i] = layer_density(*scratch.layer[i], h[i], exponent[i]);
}

void sample_medium_block(const Atmosphere& atm, const double* h, size_t n, NodeExp exp_kind,
                         MediumBlock& out) {
  // Each present component's densities in a row of its own and its
  // coefficients once, then each altitude's sums in registers, in
  // sample_medium's order: no zeroed arrays added to once per component.
  out.present.clear();
  for (const MediumComponent& c : atm.components)
    if (!c.density.layers.empty())  // else density_at is 0: sample_medium adds nothing
      out.present.push_back({c.scattering_per_m, c.scattering_per_m + c.absorption_per_m});
  const size_t rows = out.present.size();
  out.density.resize(rows * n);
  size_t row = 0;
  for (const MediumComponent& c : atm.components)
    if (!c.density.layers.empty())
      density_block(c.density, h, n, exp_kind, out, out.density.data() + n * row++);
  out.scattering.resize(n);
  out.extinction.resize(n);
  for (size_t i = 0; i < n; ++i) {
    glm::dvec3 scattering(0.0), extinction(0.0);
    for (size_t k = 0; k < rows; ++k) {
      const double d = out.density[n * k + i];
      if (d == 0.0) continue;
      scattering += d * out.present[k].scattering;
      extinction += d * out.present[k].extinction;
    }
    out.scattering[i] = scattering;
    out.extinction[i] = extinction;
  }
}

}  // namespace skybake

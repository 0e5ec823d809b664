#include "atmosphere/medium_block.hpp"

#include <algorithm>
#include <cmath>

#include "core/exp_block.hpp"

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
  // and loops the compiler vectorizes.
  const DensityLayer* only = profile.layers.size() == 1 ? &profile.layers[0] : nullptr;
  scratch.exponent.resize(n);
  scratch.layer.resize(n);
  for (size_t i = 0; i < n; ++i) {
    scratch.layer[i] = only ? only : &layer_at(profile, h[i]);
    scratch.exponent[i] = scratch.layer[i]->exp_scale_per_m * h[i];
  }
  if (exp_kind == NodeExp::block) {
    for (size_t i = 0; i < n; ++i)
      scratch.exponent[i] = std::min(std::max(scratch.exponent[i], -708.0), 708.0);
    exp_block(scratch.exponent.data(), n);
  } else {
    for (size_t i = 0; i < n; ++i) scratch.exponent[i] = std::exp(scratch.exponent[i]);
  }
  if (only) {
    for (size_t i = 0; i < n; ++i) density[i] = layer_density(*only, h[i], scratch.exponent[i]);
    return;
  }
  for (size_t i = 0; i < n; ++i)
    density[i] = layer_density(*scratch.layer[i], h[i], scratch.exponent[i]);
}

void sample_medium_block(const Atmosphere& atm, const double* h, size_t n, NodeExp exp_kind,
                         MediumBlock& out) {
  out.scattering.assign(n, glm::dvec3(0.0));
  out.extinction.assign(n, glm::dvec3(0.0));
  out.density.resize(n);
  for (const MediumComponent& c : atm.components) {
    if (c.density.layers.empty()) continue;  // density_at is 0: sample_medium adds nothing
    density_block(c.density, h, n, exp_kind, out, out.density.data());
    const glm::dvec3 sigma_t = c.scattering_per_m + c.absorption_per_m;
    for (size_t i = 0; i < n; ++i) {
      const double d = out.density[i];
      if (d == 0.0) continue;
      out.scattering[i] += d * c.scattering_per_m;
      out.extinction[i] += d * sigma_t;
    }
  }
}

}  // namespace skybake

// sample_medium (medium.hpp) at many altitudes in one pass per component, so
// that the exponentials of the density profiles are taken in one vectorized
// block (core/kernels/exp_block.hpp) instead of one std::exp call each: the marches
// of the error records' references (psi_ms_reference.cpp), where the
// calls were a large part of the time.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/extinction_profile.hpp"
#include "atmosphere/medium.hpp"

namespace skybake {

struct MediumBlock {
  std::vector<glm::dvec3> scattering, extinction;  // per altitude, as MediumSample
  std::vector<double> density, exponent;           // scratch
  std::vector<const DensityLayer*> layer;          // scratch
  // Scratch: the coefficients of the components with a density profile.
  struct Coefficients {
    glm::dvec3 scattering, extinction;
  };
  std::vector<Coefficients> present;
};

// density[i] = density_at(profile, h[i]), i < n, the exponentials as below;
// `scratch`'s exponent and layer arrays are used.
void density_block(const DensityProfile& profile, const double* h, size_t n, NodeExp exp_kind,
                   MediumBlock& scratch, double* density);

// out.scattering[i] and out.extinction[i] = sample_medium(atm, h[i]), i < n.
// NodeExp::libm: the same bits (std::exp, the same operations in the same
// order). NodeExp::block: exp_block's exponentials (within 3e-16 relative of
// std::exp; arguments clamped to [-708, 708], where the density is 0 or 1
// to 1e-307 after its clamp).
void sample_medium_block(const Atmosphere& atm, const double* h, size_t n, NodeExp exp_kind,
                         MediumBlock& out);

}  // namespace skybake

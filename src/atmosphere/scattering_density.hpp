// The scattering density J_k of one order of the 4D table (Bruneton 2017
// ComputeScatteringDensity; the equation, the phase quadrature and how the
// work is shared between texels are in scattering_orders.hpp).
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/incident_radiance.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sun_frame_density.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

// J_k at (r, mu, mu_s, nu) by the direct quadrature over the grid: the
// reference for bake_scattering_density, which must agree (tests).
glm::dvec3 compute_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                                      const ScatteringShape& shape, const ScatteringOrder& previous,
                                      const GroundIrradiance& ground, double r, double mu,
                                      double mu_s, double nu, int bands);

// J_k at every texel (RGB, the scattering table's shape), fast path.
Texture bake_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                                const ScatteringShape& shape, const ScatteringOrder& previous,
                                const GroundIrradiance& ground, int bands, const BakeContext& ctx);
// The same into `out`, whose buffer is kept when it has the table's shape
// (every texel is written): the orders reuse one, where a fresh table each
// order made the kernel fault in and clear its pages (scattering_orders.cpp).
void bake_scattering_density(const Atmosphere& atm, const Texture& transmittance_lut,
                             const ScatteringShape& shape, const ScatteringOrder& previous,
                             const GroundIrradiance& ground, int bands, const BakeContext& ctx,
                             Texture& out);

// J_k in the sun's frame (sun_frame_density.hpp), phi_size >= 2 texels of
// cos_phi, into `out` (its buffer kept when it has the size): J itself,
// which density_per_scattering's sun-frame overload divides by sigma_s.
void bake_sun_frame_density(const Atmosphere& atm, const Texture& transmittance_lut,
                            const ScatteringShape& shape, const ScatteringOrder& previous,
                            const GroundIrradiance& ground, int bands, int phi_size,
                            const BakeContext& ctx, SunFrameDensity& out);

}  // namespace skybake

// Sky-view layers whose multiple scattering comes from Bruneton's 4D order
// iteration instead of Hillaire's Psi_ms (docs/reference.md "Sky-view with
// the 4D table's orders >= 2"): per texel, the single scattering marched as
// in skyview_lut.hpp (Psi_ms = 0) plus the iteration's orders >= 2 toward
// the texel's direction, read from the 4D table (sum of DeltaS_k, the
// geometric tail included) at (r, mu, mu_s, nu). Same shape, axes, units and
// lookup_skyview as skyview_lut.hpp. The iteration is the converged field of
// converged_multiscattering.hpp, computed in memory.
// Reads: the transmittance LUT.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/skyview_lut.hpp"

namespace skybake {

// Orders >= 2 of the field toward `view` from radius r (clamped to the
// shell) under a sun of zenith angle sun_zenith_rad, units of the sun's
// illuminance (as the sky-view's luminance). Thread-safe.
glm::dvec3 lookup_field_multiple_scattering(const Atmosphere& atm, const ConvergedField& field,
                                            double r, SkyviewDirection view,
                                            double sun_zenith_rad);

// The layers of spec, single scattering marched plus the field's orders >= 2.
Texture bake_skyview_lut_multiple4d(const Atmosphere& atm, const Texture& transmittance_lut,
                                    const ConvergedField& field, const SkyviewLutSpec& spec,
                                    const BakeContext& ctx);

}  // namespace skybake

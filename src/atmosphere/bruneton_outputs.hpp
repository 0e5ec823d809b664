// The textures bake_bruneton returns (shapes and channels in
// scattering_orders.hpp), assembled from the sums of the iteration, and the
// metadata that tells a reader how to map and combine them.
#pragma once

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/texture.hpp"

namespace skybake {

// Fills out.scattering (the accumulated RGB, + single Mie red in A with
// combined_mie_alpha), out.single_mie and out.irradiance, and the metadata
// of all four textures; out.direct_irradiance, the shape, the orders and the
// tail must be set.
void assemble_bruneton_outputs(const Atmosphere& atm, const BrunetonSpec& spec,
                               const Texture& accumulated, Texture single_mie, Texture irradiance,
                               BrunetonTextures& out);

}  // namespace skybake

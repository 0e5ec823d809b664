// The precomputed-scattering families as the products bake them
// (bruneton_products.cpp): one bake_bruneton() / bake_scattering3d() per
// scene and settings, cached for the process, so that every product of a
// family and its error measurement (error_measures.hpp) read the same bake.
// A miss bakes the family (it reads the scene's transmittance input).
#pragma once

#include <memory>

#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "pipeline/product.hpp"

namespace skybake {

std::shared_ptr<const BrunetonTextures> bruneton_family(const Scene& scene, const ProductInputs& in,
                                                        const BakeContext& ctx);
std::shared_ptr<const Scattering3dTextures> scattering3d_family(const Scene& scene,
                                                                const ProductInputs& in,
                                                                const BakeContext& ctx);

// Empties both caches, so that the next request bakes again: for a benchmark
// that bakes one scene several times in a process (bench/error_records_cpu.cpp),
// where every bake after the first would time a cache hit.
void forget_families();

}  // namespace skybake

// What a runtime shader needs besides a product's own parameterization,
// added to every computed texture's metadata (docs/formats.md "Metadata"):
// the filter and per-axis wrap modes of its product (ProductInfo::sampling),
// and on atmosphere tables the solar irradiance the values are relative to
// and, where the values depend on it, the Mie phase model and its g.
#pragma once

#include "core/texture.hpp"
#include "pipeline/product.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Records the first 2 wrap modes of the product, 3 for a volume. Throws Error
// when the product has fewer modes than the texture axes: a registry mistake.
void add_runtime_metadata(const Scene& scene, const ProductInfo& product, Texture& tex);

// "cornette_shanks", "henyey_greenstein", "none" or "mixed" and g (0 unless
// one phase): the Mie model of the atmosphere's scattering components, and
// with "mixed" each component's phase and g as component.<name>.phase / .g.
void set_mie_phase_metadata(const Atmosphere& atm, Metadata& meta);

}  // namespace skybake

// The "convention" key of the Hillaire-family outputs (transmittance,
// multiscattering, skyview, aerial_perspective; atmosphere/table_convention.hpp):
// the scene-level default, the rules a convention puts on an output, and the
// twin in skybake's own layout that the bakers reading a table get
// (docs/decisions/table-convention-key.md).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/texture.hpp"
#include "pipeline/product.hpp"

namespace skybake {

// The output's convention ("convention" in its options; skybake when absent).
TableConvention output_convention(const OutputSpec& spec);

// Whether the product takes the key (its schema lists it).
bool takes_convention(const std::string& product);

// Before an output object is checked: an output of a product that takes the
// key and gives none inherits the scene's "convention"; under hillaire_demo
// an aerial_perspective output without depth_range_km gets the demo's
// 128 km (32 slices of 4 km).
void apply_scene_convention(const nlohmann::json& scene_doc, nlohmann::json& out);

// After: skybake's own layout, and "fit_demo_march": false, are recorded as
// no key at all, so that naming them changes no hash.
void normalize_convention(OutputSpec& spec);

// The rules hillaire_demo puts on an output (pointers relative to it).
std::vector<ProductProblem> convention_problems(const OutputSpec& spec);

// The output in skybake's layout: what a baker that reads the table gets
// (without a fit to Hillaire's demo march).
OutputSpec skybake_layout_twin(const OutputSpec& spec);

// A multiscattering output with "fit_demo_march": its Psi_ms rows scaled for
// Hillaire's demo march (atmosphere/hillaire_demo_march_fit.hpp).
bool fits_demo_march(const OutputSpec& spec);
// Scales `multiscattering` (his layout) so, the fit reading the transmittance
// in his layout at the size of `transmittance` (any layout).
void fit_to_demo_march(const Atmosphere& atm, const Texture& transmittance,
                       Texture& multiscattering);

}  // namespace skybake

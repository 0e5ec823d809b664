// A spectral scene's tables (docs/decisions/spectral-tables.md): every
// needed node of the product graph baked at the three wavelengths of one
// group, converted through the group's colour matrix and added to the
// output, group after group (Bruneton 2017's precomputed luminance). Time
// grows with the number of groups; memory holds one group's tables, the
// outputs' running sums waiting on disk in between, whatever the number of
// wavelengths.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/bake_context.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

// How a table's values add up over wavelengths.
enum class SpectralRule {
  radiance,   // linear in the sun: RGB = sum of M_g L_g
  sun_mean,   // a per-wavelength factor (transmittance, Psi_ms): the sun-weighted
              // mean, sum of M_g F_g divided by the sun's colour, channel by channel
};

SpectralRule spectral_rule(const std::string& product);

struct SpectralTables {
  std::vector<std::optional<Texture>> textures;
  // Per node with measured[i]: the error record (error_measures.hpp) of the
  // wavelength group whose table is farthest from its reference, each group
  // measured at its own three wavelengths, with "wavelength_groups" and
  // "worst_group_nm"; null for the other nodes.
  std::vector<nlohmann::json> errors;
};

// The textures of graph.nodes[i] for every i with needed[i], the others
// empty. scene.spectral must be set. Between groups the running sums wait
// in an unnamed file in spill_folder (io/texel_spill.hpp); empty: in memory.
SpectralTables bake_spectral_graph(const Scene& scene, const ProductGraph& graph,
                                   const std::vector<char>& needed,
                                   const std::vector<char>& measured, const BakeContext& ctx,
                                   const std::filesystem::path& spill_folder = {});

// What a spectral table's metadata records (docs/formats.md "Metadata"):
// spectral_wavelengths, spectral_range_nm, colour_space, spectral_units,
// luminance_scale_cd_m2 and spectral_quantity (radiance, luminance or
// sun_weighted_mean).
void add_spectral_metadata(const SpectralScene& spectral, const ProductInfo& product, Texture& tex);

}  // namespace skybake

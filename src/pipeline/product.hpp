// The product registry: every asset skybake can bake, what it reads, its
// default and maximum size, and the function that bakes it. pipeline/ is the
// only layer that knows every product; bakers in atmosphere/, noise/ and
// clouds/ are pure functions that know nothing of presets or files.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Baked textures of the products a baker depends on, by product name.
using ProductInputs = std::map<std::string, const Texture*>;

// A product-specific rule broken by an output: pointer relative to the output
// object ("/size", "/worley/2/period"), and the rule with what was found.
struct ProductProblem {
  std::string pointer;
  std::string rule;
};
using CheckFn = std::function<std::vector<ProductProblem>(const OutputSpec&)>;

// Measured error of a baked table as an engine reads it, against a reference
// that does not use it (pipeline/error_measures.hpp): the manifest's "error".
using MeasureFn = std::function<nlohmann::json(const Scene&, const OutputSpec&,
                                               const ProductInputs&, const Texture&)>;

using BakeFn = std::function<Texture(const Scene&, const OutputSpec&, const ProductInputs&,
                                     const BakeContext&)>;

// How an engine samples a product's texture (docs/formats.md "Metadata"):
// the filter, and the wrap mode of each texture axis (u, v, then w for a
// volume; a 2D array's layers are never filtered across). Recorded in every
// output's metadata as filter, wrap_u, wrap_v, wrap_w.
struct Sampling {
  std::string filter = "linear";
  std::vector<std::string> wrap = {"clamp", "clamp"};  // "clamp" (to edge) or "repeat"
};

struct ProductInfo {
  std::string name;                          // "transmittance"
  std::string summary;                       // one line for --help and plan
  std::vector<std::string> axes;             // size axes in preset order, e.g. {"mu", "r"}
  std::vector<int> default_size;             // one per axis
  std::vector<int> max_size;                 // one per axis; larger is refused at load
  std::vector<std::string> default_formats;  // when the preset gives none
  std::vector<std::string> allowed_formats;  // subset of exr, dds, vdb, png
  std::vector<std::string> dependencies;     // products whose textures bake() reads
  std::vector<std::string> scene_sections;   // top-level preset keys the result depends on
  // DXGI name, "unorm8" (R8_UNORM for one channel, else R8G8B8A8_UNORM), or
  // empty (float32 RGBA, or half with precision "half").
  std::string default_dds_format;
  // exr_compression when the output gives none (docs/decisions/exr-compression.md: chosen per product family by measurement).
  std::string default_exr_compression = "zip";
  // vdb_compression when the output gives none (same measurements).
  std::string default_vdb_compression = "blosc";
  BakeFn bake;
  // A product whose texture is not linear in the light (a tone-mapped
  // picture): what a spectral bake bakes per wavelength group instead (the
  // linear radiance, summed over groups), and what turns the sum into the
  // product's texture. Empty: bake, and the sum is the texture.
  BakeFn spectral_group_bake;
  std::function<Texture(Texture, const Scene&, const OutputSpec&)> finish_spectral_sum;
  // Rough cost for farm scheduling: single-thread nanoseconds per output
  // texel at default settings (measured with bench/); `plan` sums it into
  // each farm node's estimated_seconds (docs/farm.md).
  double ns_per_texel = 1000.0;
  // Semantic checks at load time beyond the schema; empty = none.
  CheckFn check;
  // A cube map (layers six faces per cube, core/cube_map.hpp): DDS and KTX2
  // write it with the cube flags (write_dds_cube, write_ktx2_cube).
  bool cube_map = false;
  // The levels below level 0 when the product makes its own (a cube's GGX
  // prefiltered chain); they replace the box chain and are always written.
  std::function<std::vector<Texture>(const Texture&, const OutputSpec&)> lower_levels;
  // Float channels go to DDS and KTX2 as half whatever the output's
  // precision (its dds_format or ktx2_format still chooses another format).
  bool half_files = false;
  bool default_mips = false;     // DDS mip chain unless the output says "mips"
  bool preview_tiled = false;    // PNG preview repeats each panel 2x2 (tileable textures)
  bool preview_split = false;    // PNG preview shows each channel as its own grey panel
  MeasureFn measure_error;       // empty: exact, a picture, or tileable (below)
  bool tileable = false;  // records check-tiling's verdict (error_measures.hpp tiling_record)
  // A density-like volume (the cloud noises): its VDB grids are fog volumes
  // and, unless the output names them (grid_names), its first channel's grid
  // is "density" (docs/formats.md "VDB").
  bool density_volume = false;
  Sampling sampling;      // filter and wrap modes, in the metadata of every output
  // Values relative to the preset's sun: records solar_irradiance.
  bool atmosphere_table = false;
  // Values depend on the Mie phase function: records mie_phase and mie_g.
  bool reads_mie_phase = false;
};

// All products, in a stable order (dependencies before dependents).
const std::vector<ProductInfo>& product_registry();

// nullptr when unknown.
const ProductInfo* find_product(const std::string& name);

// Names of all products, for messages ("expected one of ...").
std::vector<std::string> product_names();

}  // namespace skybake

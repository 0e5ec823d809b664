#include "pipeline/spectral_bake.hpp"

#include <algorithm>

#include "atmosphere/order_progress.hpp"
#include "core/error.hpp"
#include "core/spectral_data.hpp"
#include "io/texel_spill.hpp"
#include "pipeline/bruneton_families.hpp"
#include "pipeline/table_conventions.hpp"

namespace skybake {

SpectralRule spectral_rule(const std::string& product) {
  return product == "transmittance" || product == "multiscattering" ? SpectralRule::sun_mean
                                                                    : SpectralRule::radiance;
}

namespace {

// One group's tables, in graph order, and their twins in skybake's layout
// for the nodes written in another convention (bake.cpp does the same).
struct SpectralGroupTables {
  std::vector<std::optional<Texture>> tables, twins;
  ProductInputs inputs_of(const GraphNode& node, const ProductGraph& graph) const {
    ProductInputs in;
    for (size_t d : node.deps) in[graph.nodes[d].info->name] = twins[d] ? &*twins[d] : &*tables[d];
    return in;
  }
};

bool spectral_has_dependents(const ProductGraph& graph, size_t i) {
  for (const GraphNode& other : graph.nodes)
    if (std::find(other.deps.begin(), other.deps.end(), i) != other.deps.end()) return true;
  return false;
}

// The 4D and 3D tables' combined alpha is the single Mie's red (Bruneton
// 2017's combined texture): it adds up from the family's RGB single Mie.
bool spectral_has_mie_alpha(const std::string& product, const Texture& tex) {
  return (product == "scattering" || product == "scattering3d") && tex.channels.size() == 4;
}

class SpectralMieAlpha {
 public:
  SpectralMieAlpha(const std::string& product, const Texture& tex, const Scene& sg,
                   const ProductInputs& in, const BakeContext& ctx) {
    if (!spectral_has_mie_alpha(product, tex)) return;
    if (product == "scattering")
      bruneton_ = bruneton_family(sg, in, ctx);
    else
      scattering3d_ = scattering3d_family(sg, in, ctx);
  }
  const Texture* texture() const {
    if (bruneton_) return &bruneton_->single_mie;
    if (scattering3d_) return &scattering3d_->mie;
    return nullptr;
  }

 private:
  std::shared_ptr<const BrunetonTextures> bruneton_;
  std::shared_ptr<const Scattering3dTextures> scattering3d_;
};

// The sum of the group's luminance weights: the Y row of its XYZ matrix
// applied to 1, for the channels that are neither RGB nor radiance.
double spectral_group_luminance(const SpectralScene& s, const SpectralGrid& grid, size_t g) {
  const glm::dmat3 xyz = group_colour_matrix(grid, g, s.medium.sun_w_m2_nm, glm::dmat3(1.0));
  return (xyz * glm::dvec3(1.0)).y;
}

// The record of the group farthest from its reference (largest max_rel).
void keep_worst_error(nlohmann::json& worst, nlohmann::json group, const glm::dvec3& nm,
                      size_t groups) {
  if (!group.is_object()) return;
  const double max_rel = group.value("max_rel", 0.0);
  if (worst.is_object() && worst.value("max_rel", 0.0) >= max_rel) return;
  group["wavelength_groups"] = groups;
  group["worst_group_nm"] = {nm.x, nm.y, nm.z};
  group["reference"] = group.value("reference", std::string()) +
                       "; each wavelength group's table against its own reference at its three "
                       "wavelengths, the worst group recorded";
  worst = std::move(group);
}

// A group's channels are wavelengths: the table's energy balance is the
// worst over every wavelength, in all three channels.
void keep_largest_energy_balance(Metadata& out, const Metadata& group) {
  const glm::dvec3* a = find_meta<glm::dvec3>(out, "energy_out_over_in");
  const glm::dvec3* b = find_meta<glm::dvec3>(group, "energy_out_over_in");
  if (!a || !b) return;
  const double worst = std::max({a->x, a->y, a->z, b->x, b->y, b->z});
  set_meta(out, "energy_out_over_in", glm::dvec3(worst));
}

// The group's table turned in place into its share of the output: M * rgb
// texel by texel; a fourth channel weight * value, or for the 4D table's
// combined Mie alpha the red of M times the group's single Mie (Bruneton
// 2017, the combined texture).
void spectral_share_in_place(Texture& group, const glm::dmat3& m, double weight,
                             const Texture* single_mie) {
  const size_t nc = group.channels.size(), texels = group.texel_count();
  if (nc < 3) throw Error("spectral bake: a table with fewer than three channels");
  for (size_t t = 0; t < texels; ++t) {
    float* v = &group.data[t * nc];
    const glm::dvec3 rgb = m * glm::dvec3(v[0], v[1], v[2]);
    for (int c = 0; c < 3; ++c) v[c] = float(rgb[c]);
    if (nc < 4) continue;
    if (single_mie) {
      const float* mie = &single_mie->data[t * 3];
      v[3] = float((m * glm::dvec3(mie[0], mie[1], mie[2])).x);
    } else {
      v[3] = float(weight * v[3]);
    }
  }
}

// The sun-weighted means of a sun_mean table, and the luminance-weighted
// mean of any fourth channel other than the combined Mie.
void spectral_finish(Texture& out, SpectralRule rule, const glm::dvec3& sun, double luminance,
                     bool mie_alpha) {
  const size_t nc = out.channels.size(), texels = out.texel_count();
  for (size_t t = 0; t < texels; ++t) {
    float* v = &out.data[t * nc];
    if (rule == SpectralRule::sun_mean)
      for (int c = 0; c < 3; ++c) v[c] = float(v[c] / sun[c]);
    if (nc >= 4 && !mie_alpha) v[3] = float(v[3] / luminance);
  }
}

}  // namespace

void add_spectral_metadata(const SpectralScene& spectral, const ProductInfo& product,
                           Texture& tex) {
  if (std::find(product.scene_sections.begin(), product.scene_sections.end(), "atmosphere") ==
      product.scene_sections.end())
    return;
  set_meta(tex.metadata, "spectral_wavelengths", spectral.grid().wavelength_count());
  set_meta(tex.metadata, "spectral_range_nm", glm::dvec2(kSpectrumMinNm, kSpectrumMaxNm));
  set_meta(tex.metadata, "spectral_sampling", spectral_sampling_name(spectral.sampling));
  set_meta(tex.metadata, "colour_space", colour_space_name(spectral.colour_space));
  set_meta(tex.metadata, "spectral_units", spectral_units_name(spectral.units));
  // The factor from the table's units to cd/m^2 (the sun's to lux): what a
  // photometric renderer multiplies by in the shader (half floats hold the
  // table, not the product).
  SpectralScene photometric = spectral;
  photometric.units = SpectralUnits::photometric;
  const glm::dmat3 to_xyz = xyz_from_rgb(chromaticities_of(spectral.colour_space));
  set_meta(tex.metadata, "luminance_scale_cd_m2",
           (to_xyz * photometric.sun_colour()).y / (to_xyz * spectral.sun_colour()).y);
  // The bakers describe their three wavelengths; a spectral table has many.
  if (auto it = tex.metadata.find("quantity"); it != tex.metadata.end())
    if (auto* q = std::get_if<std::string>(&it->second))
      if (size_t at = q->find("R/G/B at 680/550/440 nm"); at != std::string::npos)
        q->replace(at, std::string::npos, "RGB in colour_space (spectral_quantity)");
  const bool mean = spectral_rule(product.name) == SpectralRule::sun_mean;
  set_meta(tex.metadata, "spectral_quantity",
           std::string(mean                                           ? "sun_weighted_mean"
                       : spectral.units == SpectralUnits::photometric ? "luminance"
                                                                      : "radiance"));
}

SpectralTables bake_spectral_graph(const Scene& scene, const ProductGraph& graph,
                                   const std::vector<char>& needed,
                                   const std::vector<char>& measured, const BakeContext& ctx,
                                   const std::filesystem::path& spill_folder) {
  const SpectralScene& s = *scene.spectral;
  const SpectralGrid grid = s.grid();
  const size_t n = graph.nodes.size(), groups = grid.groups.size();
  SpectralTables result{std::vector<std::optional<Texture>>(n), std::vector<nlohmann::json>(n)};
  std::vector<std::optional<Texture>>& out = result.textures;
  glm::dvec3 sun(0.0);
  double luminance = 0.0;
  // The running sums wait on disk while the next group's tables are made,
  // and each group's table becomes its share of the sum in place: the
  // bake's peak memory is then the RGB bake's.
  TexelSpill sums(groups > 1 ? spill_folder : std::filesystem::path());
  std::vector<Metadata> meta(n);
  for (size_t g = 0; g < groups; ++g) {
    Scene sg = scene;
    sg.spectral = nullptr;
    sg.atmosphere = atmosphere_at_wavelengths(scene.atmosphere, s.medium, grid.groups[g]);
    // The 4D and 3D families are cached by the atmosphere section: one entry per group.
    sg.resolved["atmosphere"]["spectral_group_nm"] = {grid.groups[g][0], grid.groups[g][1],
                                                      grid.groups[g][2]};
    const glm::dmat3 m = s.group_matrix(grid, g);
    const double weight = spectral_group_luminance(s, grid, g);
    sun += m * glm::dvec3(1.0);
    luminance += weight;
    const BakeContext gctx = stage_context(ctx, double(g) / groups, double(g + 1) / groups);
    SpectralGroupTables t{std::vector<std::optional<Texture>>(n),
                          std::vector<std::optional<Texture>>(n)};
    std::vector<std::optional<SpectralMieAlpha>> mie(n);
    for (size_t i = 0; i < n; ++i) {
      if (!needed[i]) continue;
      const GraphNode& node = graph.nodes[i];
      const ProductInputs in = t.inputs_of(node, graph);
      const BakeFn& bake =
          node.info->spectral_group_bake ? node.info->spectral_group_bake : node.info->bake;
      t.tables[i] = bake(sg, node.spec, in, gctx);
      if (output_convention(node.spec) != TableConvention::skybake &&
          spectral_has_dependents(graph, i))
        t.twins[i] = node.info->bake(sg, skybake_layout_twin(node.spec), in, {});
      if (measured[i])
        keep_worst_error(result.errors[i],
                         node.info->measure_error(sg, node.spec, in, *t.tables[i]), grid.groups[g],
                         groups);
      mie[i].emplace(node.info->name, *t.tables[i], sg, in, gctx);
    }
    // Once every table of the group is made (the later ones read the
    // earlier), each becomes its share and takes the sum so far.
    for (size_t i = 0; i < n; ++i) {
      if (!t.tables[i]) continue;
      Texture& table = *t.tables[i];
      if (g == 0) meta[i] = table.metadata;
      keep_largest_energy_balance(meta[i], table.metadata);
      spectral_share_in_place(table, m, weight, mie[i]->texture());
      sums.add_to(i, table);
      if (g + 1 < groups) {
        sums.put(i, table);
      } else {
        out[i] = std::move(table);
        out[i]->metadata = meta[i];
      }
    }
    forget_families();
  }
  for (size_t i = 0; i < n; ++i) {
    if (!out[i]) continue;
    const ProductInfo& info = *graph.nodes[i].info;
    spectral_finish(*out[i], spectral_rule(info.name), sun, luminance,
                    spectral_has_mie_alpha(info.name, *out[i]));
    if (info.finish_spectral_sum)
      out[i] = info.finish_spectral_sum(std::move(*out[i]), scene, graph.nodes[i].spec);
  }
  return result;
}

}  // namespace skybake

#include "pipeline/output_writer.hpp"

#include <algorithm>
#include <memory>
#include <optional>
#include <variant>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/mip_chain.hpp"
#include "io/atomic_file.hpp"
#include "io/dds.hpp"
#include "io/exr.hpp"
#include "io/file_record.hpp"
#include "io/ktx2.hpp"
#include "io/png_preview.hpp"
#include "io/vdb.hpp"
#include "pipeline/dds_output.hpp"
#include "pipeline/ktx2_output.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {

namespace {

// The output's grid_names, else for a density volume "density" for the
// first channel and the channel names for the others (docs/decisions/vdb-grids.md); fog-volume class for density volumes.
VdbWriteOptions vdb_options(const Texture& tex, const ProductInfo& info, const OutputSpec& spec) {
  VdbWriteOptions options;
  options.finite = FiniteCheck::already_checked;
  options.voxel_size = 1.0 / tex.width;
  if (spec.options.contains("grid_names")) {
    options.grid_names = spec.options["grid_names"].get<std::vector<std::string>>();
  } else if (info.density_volume) {
    options.grid_names = tex.channels;
    options.grid_names[0] = "density";
  }
  if (info.density_volume) options.grid_class = VdbGridClass::fog_volume;
  options.compression = vdb_compression_from_name(
      option_string(spec, "vdb_compression", info.default_vdb_compression));
  return options;
}

// Pixels a preview panel has at least along each axis (png_preview.hpp min_side).
constexpr int kPreviewMinSide = 64;

// The label of each panel a texture's metadata describes (a sky preview's
// panel_<i>, its sun elevation and camera altitude): "SUNSET: SUN 0 DEG,
// CAMERA AT 200 M"; none when it describes none.
std::vector<std::string> panel_labels(const Texture& tex) {
  std::vector<std::string> labels;
  for (int i = 0;; ++i) {
    const std::string key = fmt::format("panel_{}", i);
    const auto name = tex.metadata.find(key);
    if (name == tex.metadata.end() || !std::holds_alternative<std::string>(name->second)) break;
    std::string label = std::get<std::string>(name->second);
    std::replace(label.begin(), label.end(), '_', ' ');
    const auto sun = tex.metadata.find(key + "_sun_elevation_deg");
    if (sun != tex.metadata.end() && std::holds_alternative<double>(sun->second))
      label += fmt::format(": SUN {} DEG", std::get<double>(sun->second));
    const auto alt = tex.metadata.find(key + "_camera_altitude_m");
    if (alt != tex.metadata.end() && std::holds_alternative<double>(alt->second)) {
      const double m = std::get<double>(alt->second);
      label += m < 1e4 ? fmt::format(", CAMERA AT {:.0f} M", m)
                       : fmt::format(", CAMERA AT {:.0f} KM", m / 1e3);
    }
    labels.push_back(label);
  }
  return labels;
}

// What the formats of one output share: the lower mip levels, built once
// for DDS and KTX2 alike, and the block-compressed slices of every level,
// encoded once for both (BC encoding is most of their writing).
struct SharedLevels {
  std::optional<std::vector<Texture>> lower;
  BcSliceCache bc;

  MipLevels levels(const Texture& tex, bool mips, const ProductInfo& info,
                   const OutputSpec& spec) {
    MipLevels out{&tex};
    if (info.lower_levels) {
      if (!lower) lower = info.lower_levels(tex, spec);
    } else if (!mips) {
      return out;
    }
    if (!lower) lower = build_lower_mips(tex, MipEdge::wrap);
    for (const Texture& level : *lower) out.push_back(&level);
    return out;
  }
};

// Writes `tex` to `tmp` in one format; returns the encoding it used. The
// caller has run check_finite on `tex` (write_outputs: once for every format).
std::string write_format(const std::string& format, const std::string& tmp, const Texture& tex,
                         const ProductInfo& info, const OutputSpec& spec, SharedLevels& shared) {
  if (format == "exr") {
    const bool half = spec.precision == "half";
    write_exr(tmp, tex, half ? ExrPrecision::half : ExrPrecision::float32, ExrVolumeLayout::atlas,
              exr_compression_from_name(
                  option_string(spec, "exr_compression", info.default_exr_compression)),
              FiniteCheck::already_checked);
    return half ? "half" : "float";
  }
  if (format == "dds") {
    const DdsFormat dds = output_dds_format(spec, info, tex.channel_count());
    const bool mips = spec.options.value("mips", info.default_mips);
    const MipLevels levels = shared.levels(tex, mips, info, spec);
    if (info.cube_map)
      write_dds_cube(tmp, levels, dds, FiniteCheck::already_checked);
    else
      write_dds(tmp, levels, dds, output_dds_header(spec, dds, tex.layers),
                FiniteCheck::already_checked, &shared.bc);
    return dxgi_format_name(dds);
  }
  if (format == "ktx2") {
    const Ktx2Format ktx2 = output_ktx2_format(spec, info, tex.channel_count());
    const bool mips = spec.options.value("mips", info.default_mips);
    const MipLevels levels = shared.levels(tex, mips, info, spec);
    if (info.cube_map)
      write_ktx2_cube(tmp, levels, ktx2, FiniteCheck::already_checked);
    else
      write_ktx2(tmp, levels, ktx2, FiniteCheck::already_checked, &shared.bc);
    return ktx2_format_name(ktx2);
  }
  if (format == "vdb") {
    write_vdb(tmp, tex, vdb_options(tex, info, spec));
    return "float";
  }
  if (format == "png") {
    PreviewOptions preview;
    preview.tile_2x2 = info.preview_tiled;
    preview.split_channels = info.preview_split;
    preview.finite = FiniteCheck::already_checked;
    // Small textures enlarged for the eye (cloud_types: 8 x 128); profiles
    // over height drawn rising upward.
    preview.min_side = kPreviewMinSide;
    preview.height_up = !info.axes.empty() && info.axes.back() == "height";
    preview.label_channels = preview.stretch_narrow = info.preview_split;
    preview.panel_labels = panel_labels(tex);
    if (info.preview_split) {  // channels side by side, two slices stacked: stays readable
      preview.max_slices = 2;
      preview.max_columns = 1;
    }
    write_png_preview(tmp, tex, preview);
    return "srgb8";
  }
  throw Error(fmt::format("unknown format '{}' passed validation", format));
}

}  // namespace

const std::vector<std::string>& output_formats() {
  static const std::vector<std::string> formats = {"exr", "dds", "ktx2", "vdb", "png"};
  return formats;
}

std::vector<std::string> output_files(const OutputSpec& spec) {
  std::vector<std::string> files;
  for (const std::string& format : spec.formats)
    files.push_back(format == "png" ? spec.name + ".preview.png" : spec.name + "." + format);
  return files;
}

std::vector<ManifestFile> write_outputs(const Texture& tex, const ProductInfo& info,
                                        const OutputSpec& spec,
                                        const std::filesystem::path& scene_dir,
                                        const WriteProgress& on_file) {
  std::vector<std::unique_ptr<AtomicFile>> pending;
  std::vector<ManifestFile> files;
  SharedLevels shared;
  const std::vector<std::string> names = output_files(spec);
  for (size_t i = 0; i < spec.formats.size(); ++i) {
    if (on_file) on_file(names[i], double(i) / double(spec.formats.size()));
    pending.push_back(std::make_unique<AtomicFile>(scene_dir / names[i]));
    ManifestFile record;
    record.path = names[i];
    record.format = spec.formats[i];
    // Errors name the output, not its temporary.
    pending.back()->write([&](const std::filesystem::path& tmp) {
      // Once for every format, by the first one's writer as before (the same
      // message, naming its file); the writers then skip it.
      if (i == 0) check_finite(tex, tmp.string());
      record.encoding = write_format(spec.formats[i], tmp.string(), tex, info, spec, shared);
      // Size and content as written, so freshness notices a truncated or edited file.
      record.size = stat_file(tmp).size;
      record.hash = hash_file(tmp);
    });
    files.push_back(record);
  }
  // Each file reaches the disk before its name does; one folder flush then
  // makes all the renames durable, before the manifest can name them.
  for (auto& p : pending) p->commit(AtomicFile::FolderFlush::by_caller);
  if (!pending.empty()) flush_folder_of(pending.back()->final_path());
  return files;
}

}  // namespace skybake

#include "io/texture_file.hpp"

#include <filesystem>
#include <iterator>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "io/dds.hpp"
#include "io/exr.hpp"
#include "io/ktx2.hpp"
#include "io/manifest.hpp"
#include "io/vdb.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

// The manifest entry beside the file that lists it, if any: DDS has no
// metadata block, and EXR channels do not say whether they were requested as
// half or float.
const ManifestEntry* find_manifest_entry(const Manifest& m, const fs::path& file,
                                         const ManifestFile** file_record) {
  for (const auto& [name, entry] : m.entries)
    for (const ManifestFile& f : entry.files)
      if (f.path == file.filename().string()) {
        *file_record = &f;
        return &entry;
      }
  return nullptr;
}

void attach_manifest_metadata(const fs::path& file, Texture& tex) {
  const Manifest m = read_manifest(file.parent_path() / "manifest.json");
  const ManifestFile* record = nullptr;
  if (const ManifestEntry* entry = find_manifest_entry(m, file, &record))
    for (const auto& [k, v] : metadata_from_json(entry->metadata))
      if (!tex.metadata.count(k)) tex.metadata[k] = v;
}

std::string manifest_encoding(const fs::path& file) {
  const Manifest m = read_manifest(file.parent_path() / "manifest.json");
  const ManifestFile* record = nullptr;
  return find_manifest_entry(m, file, &record) ? record->encoding : "unknown";
}

LoadedTexture load_dds(const std::string& path, uint64_t budget) {
  const DdsHeaderInfo h = read_dds_header(path);
  DdsImage image = read_dds(path, budget);
  LoadedTexture out;
  out.format = "dds";
  out.encoding = dxgi_format_name(image.format);
  out.mip_levels = int(image.mips.size());
  out.texture = std::move(image.mips.front());
  out.lower_levels.assign(std::make_move_iterator(image.mips.begin() + 1),
                          std::make_move_iterator(image.mips.end()));
  out.details = {{"flags", fmt::format("0x{:08x}", h.flags)},
                 {"pitch_or_linear_size", h.pitch_or_linear_size},
                 {"mip_map_count", h.mip_map_count},
                 {"caps", fmt::format("0x{:08x}", h.caps)},
                 {"caps2", fmt::format("0x{:08x}", h.caps2)},
                 {"dxgi_format", h.dxgi_format},
                 {"resource_dimension", h.resource_dimension},
                 {"array_size", h.array_size},
                 {"misc_flag", fmt::format("0x{:x}", h.misc_flag)},
                 {"file_size", h.file_size}};
  if (!h.has_dx10) {  // no DDS_HEADER_DXT10: the pixel format says what the data is
    for (const char* key : {"dxgi_format", "resource_dimension", "array_size", "misc_flag"})
      out.details.erase(key);
    const DdsPixelFormat& pf = h.pixel_format;
    out.details["legacy_pixel_format"] =
        (pf.flags & dds::kDdpfFourCC)
            ? fmt::format("FourCC \"{}\" ({})", four_cc_string(pf.four_cc), pf.four_cc)
            : fmt::format("flags 0x{:x}, {} bits, masks 0x{:x} 0x{:x} 0x{:x} 0x{:x}", pf.flags,
                          pf.rgb_bit_count, pf.r_bit_mask, pf.g_bit_mask, pf.b_bit_mask,
                          pf.a_bit_mask);
  }
  attach_manifest_metadata(path, out.texture);
  return out;
}

LoadedTexture load_ktx2(const std::string& path, uint64_t budget) {
  Ktx2Image image = read_ktx2(path, budget);
  const Ktx2Header& h = image.header;
  LoadedTexture out;
  out.format = "ktx2";
  out.encoding = ktx2_format_name(image.format);
  out.mip_levels = int(image.mips.size());
  out.texture = std::move(image.mips.front());
  out.lower_levels.assign(std::make_move_iterator(image.mips.begin() + 1),
                          std::make_move_iterator(image.mips.end()));
  nlohmann::json levels = nlohmann::json::array();
  for (const Ktx2LevelIndex& l : h.levels)
    levels.push_back({{"byte_offset", l.byte_offset}, {"byte_length", l.byte_length}});
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& [key, value] : image.key_values) keys.push_back(key);
  out.details = {{"vk_format", h.vk_format},
                 {"type_size", h.type_size},
                 {"pixel_depth", h.pixel_depth},
                 {"layer_count", h.layer_count},
                 {"face_count", h.face_count},
                 {"level_count", h.level_count},
                 {"dfd_color_model", image.dfd.color_model},
                 {"dfd_color_primaries", image.dfd.color_primaries},
                 {"dfd_transfer_function", image.dfd.transfer_function},
                 {"dfd_samples", image.dfd.samples.size()},
                 {"keys", keys},
                 {"levels", levels},
                 {"file_size", h.file_size}};
  return out;
}

}  // namespace

const std::vector<std::string>& texture_file_formats() {
  static const std::vector<std::string> formats = {"exr", "dds", "ktx2", "vdb"};
  return formats;
}

LoadedTexture read_texture_file(const std::string& path, uint64_t budget) {
  const std::string ext = fs::path(path).extension().string();
  if (!fs::exists(path)) throw IoError(fmt::format("{}: no such file", path));
  // Readers open what they are given: a FIFO would block them, a device would never end.
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw IoError(fmt::format("{}: expected a regular file", path));
  if (ext == ".dds") return load_dds(path, budget);
  if (ext == ".ktx2") return load_ktx2(path, budget);
  LoadedTexture out;
  if (ext == ".exr") {
    out.texture = read_exr(path, ExrShape::recorded, budget);
    out.format = "exr";
    const ExrLayout layout = read_exr_layout(path);
    out.details = {{"layout", layout.layout}, {"parts", layout.parts}};
    if (layout.layout == "atlas")
      out.details.update({{"atlas_columns", layout.atlas_columns},
                          {"atlas_rows", layout.atlas_rows},
                          {"slice_count", layout.slice_count}});
    out.encoding = manifest_encoding(path);
  } else if (ext == ".vdb") {
    out.texture = read_vdb(path, budget);
    out.format = "vdb";
    out.encoding = "float";
  } else {
    throw IoError(fmt::format("{}: expected a .exr, .dds, .ktx2 or .vdb file, got '{}'", path, ext));
  }
  return out;
}

}  // namespace skybake

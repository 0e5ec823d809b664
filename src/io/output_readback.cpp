#include "io/output_readback.hpp"

#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "io/texture_file.hpp"

namespace skybake {

namespace {

// The DDS holds RGBA; keep the channels the product has.
Texture trimmed_to_entry(const Texture& tex, const ManifestEntry& entry) {
  Texture trimmed(tex.width, tex.height, tex.depth, tex.layers, entry.channels);
  const size_t nc = entry.channels.size(), nd = size_t(tex.channel_count());
  for (size_t t = 0; t < tex.texel_count(); ++t)
    for (size_t c = 0; c < nc; ++c) trimmed.data[t * nc + c] = tex.data[t * nd + c];
  trimmed.metadata = metadata_from_json(entry.metadata);
  return trimmed;
}

}  // namespace

std::optional<Texture> read_lossless_output(const ManifestEntry& entry,
                                            const std::filesystem::path& dir) {
  for (const ManifestFile& f : entry.files) {
    try {
      if (f.format == "exr" && f.encoding == "float") {
        Texture tex = read_texture_file((dir / f.path).string()).texture;
        if (tex.channels == entry.channels) return tex;
      }
      if (f.format == "ktx2" &&
          (f.encoding == "R32G32B32A32_SFLOAT" || f.encoding == "R32_SFLOAT")) {
        Texture tex = read_texture_file((dir / f.path).string()).texture;
        if (tex.channels == entry.channels) return tex;  // skybake.channels names them
      }
      if (f.format == "dds" && f.encoding == "R32G32B32A32_FLOAT") {
        Texture tex = read_texture_file((dir / f.path).string()).texture;
        if (tex.channel_count() >= int(entry.channels.size()))
          return trimmed_to_entry(tex, entry);
      }
    } catch (const Error&) {
      // Unreadable: the caller bakes it again.
    }
  }
  return std::nullopt;
}

}  // namespace skybake

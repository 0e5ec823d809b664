// DDS writer and reader (see dds.hpp for the layout, the channel mapping and
// the conversions; Microsoft Learn "DDS_HEADER", "DDS_HEADER_DXT10",
// "Programming Guide for DDS" for the fields and the data order).
#include "io/dds.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "io/file_bytes.hpp"
#include "core/mip_chain.hpp"
#include "core/suggest.hpp"
#include "io/block_compression.hpp"
#include "io/dds_format_table.hpp"
#include "io/le_bytes.hpp"
#include "io/size_math.hpp"

namespace skybake {
namespace {

using FormatInfo = DdsFormatInfo;

const FormatInfo* find_format(uint32_t dxgi) {
  return find_dds_format(dxgi);
}

const FormatInfo& info(DdsFormat format) {
  return dds_format_info(format);
}

std::string format_list(bool with_codes) {
  std::string s;
  for (DdsFormat format : dds_formats()) {
    if (!s.empty()) s += ", ";
    s += with_codes ? fmt::format("{} ({})", dxgi_format_name(format), uint32_t(format))
                    : dxgi_format_name(format);
  }
  return s;
}

using le::get_u32;
using le::put_u32;

// ---- shapes ----------------------------------------------------------------

struct Shape {
  int width, height, depth;
};

Shape level_shape(Shape top, int level) {
  return {std::max(1, top.width >> level), std::max(1, top.height >> level),
          std::max(1, top.depth >> level)};
}

// Refuses anything that would not make a valid DDS file, before any I/O.
void check_writable(const std::string& path, const MipLevels& mips, const FormatInfo& format,
                    DdsHeader header, FiniteCheck level0) {
  if (mips.empty()) throw IoError(path + ": expected at least one mip level, got none");
  const Texture& top = *mips[0];
  if (top.width < 1 || top.height < 1 || top.depth < 1 || top.layers < 1)
    throw IoError(fmt::format("{}: expected a non-empty texture, got {}x{}x{} with {} layers", path,
                              top.width, top.height, top.depth, top.layers));
  if (top.depth > 1 && top.layers > 1)
    throw IoError(
        fmt::format("{}: expected a volume or a 2D array (DDS has no volume arrays), "
                    "got {}",
                    path, top.shape_string()));
  if (header == DdsHeader::legacy && !format.legacy)
    throw IoError(fmt::format("{}: {} has no legacy (pre-DX10) pixel format; write it with the "
                              "DX10 header",
                              path, format.name));
  if (header == DdsHeader::legacy && top.layers > 1)
    throw IoError(fmt::format("{}: a legacy (pre-DX10) header has no array size, got {} layers; "
                              "write a 2D array with the DX10 header",
                              path, top.layers));
  if (top.channel_count() < 1 || top.channel_count() > format.components)
    throw IoError(fmt::format("{}: expected 1 to {} channels for {}, got {}", path,
                              format.components, format.name, top.channel_count()));
  const int full = mip_count(top.width, top.height, top.depth);
  if (int(mips.size()) > full)
    throw IoError(fmt::format("{}: expected at most {} mip levels for {}, got {}", path, full,
                              top.shape_string(), mips.size()));
  for (size_t i = 0; i < mips.size(); ++i) {
    const Texture& m = *mips[i];
    const Shape s = level_shape({top.width, top.height, top.depth}, int(i));
    if (m.width != s.width || m.height != s.height || m.depth != s.depth || m.layers != top.layers)
      throw IoError(fmt::format(
          "{}: mip {}: expected shape {}x{}x{} with {} layers, got "
          "{}x{}x{} with {} layers",
          path, i, s.width, s.height, s.depth, top.layers, m.width, m.height, m.depth, m.layers));
    if (m.channels != top.channels)
      throw IoError(fmt::format("{}: mip {}: expected channels [{}], got [{}]", path, i,
                                fmt::join(top.channels, ","), fmt::join(m.channels, ",")));
    if (m.data.size() != m.texel_count() * m.channels.size())
      throw IoError(fmt::format("{}: mip {}: expected {} values, got {}", path, i,
                                m.texel_count() * m.channels.size(), m.data.size()));
    if (i > 0 || level0 == FiniteCheck::run)
      check_finite(m, i == 0 ? path : fmt::format("{}: mip {}", path, i));
  }
}

// miscFlags2 of the DX10 header (dds.hpp says why).
uint32_t alpha_mode(const FormatInfo& format, int channels) {
  if (!format.has_alpha) return dds::kAlphaModeUnknown;
  return channels == 4 ? dds::kAlphaModeCustom : dds::kAlphaModeOpaque;
}

// `cube`: the layers are cube faces, six per cube (write_dds_cube).
std::vector<uint8_t> make_header(const MipLevels& mips, const FormatInfo& format,
                                 DdsHeader header, bool cube = false) {
  const Texture& top = *mips[0];
  const bool volume = top.depth > 1;
  const bool has_mips = mips.size() > 1;
  const bool dx10 = header == DdsHeader::dx10;
  std::vector<uint8_t> h(dx10 ? dds::kHeaderBytes : dds::kLegacyHeaderBytes, 0);
  uint32_t flags = dds::kDdsdCaps | dds::kDdsdHeight | dds::kDdsdWidth | dds::kDdsdPixelFormat |
                   (format.block ? dds::kDdsdLinearSize : dds::kDdsdPitch);
  if (volume) flags |= dds::kDdsdDepth;
  if (has_mips) flags |= dds::kDdsdMipMapCount;
  uint32_t caps = dds::kCapsTexture;
  if (has_mips) caps |= dds::kCapsComplex | dds::kCapsMipMap;
  if (volume || top.layers > 1) caps |= dds::kCapsComplex;
  // Row pitch, or for a block format the bytes of one top-level slice.
  const uint64_t pitch = format.block ? dds_level_bytes(format, top.width, top.height, 1)
                                      : uint64_t(top.width) * uint64_t(format.bytes);

  put_u32(&h[0], dds::kMagic);
  put_u32(&h[4], 124);  // DDS_HEADER.dwSize
  put_u32(&h[8], flags);
  put_u32(&h[12], uint32_t(top.height));
  put_u32(&h[16], uint32_t(top.width));
  put_u32(&h[20], uint32_t(pitch));
  put_u32(&h[24], volume ? uint32_t(top.depth) : 0);
  put_u32(&h[28], uint32_t(mips.size()));
  const DdsPixelFormat pf = dx10 ? DdsPixelFormat{32, dds::kDdpfFourCC, dds::kFourCCDx10}
                                 : *format.legacy;
  const uint32_t pf_fields[] = {pf.size,       pf.flags,      pf.four_cc,    pf.rgb_bit_count,
                                pf.r_bit_mask, pf.g_bit_mask, pf.b_bit_mask, pf.a_bit_mask};
  for (int i = 0; i < 8; ++i) put_u32(&h[76 + 4 * i], pf_fields[i]);
  put_u32(&h[108], caps);
  put_u32(&h[112], volume ? dds::kCaps2Volume : cube ? dds::kCaps2CubeAllFaces : 0);
  if (!dx10) return h;
  put_u32(&h[128], uint32_t(format.format));
  put_u32(&h[132], volume ? dds::kDimensionTexture3D : dds::kDimensionTexture2D);
  put_u32(&h[136], cube ? dds::kMiscTextureCube : 0);
  put_u32(&h[140], uint32_t(cube ? top.layers / 6 : top.layers));  // arraySize counts cubes
  put_u32(&h[144], alpha_mode(format, top.channel_count()));
  return h;
}

// Texels per task when encoding an uncompressed level.
constexpr size_t kEncodeGrain = size_t(1) << 14;

// Texels per write of an uncompressed level: its bytes are encoded a chunk
// at a time into one reused buffer (a whole 128^3 RGBA8 level would be 8 MB
// of fresh pages, each faulted in and zeroed).
constexpr size_t kChunkTexels = size_t(1) << 18;

// Writes one mip level of one array slice: every depth slice, in order.
// `chunk` is the caller's buffer, reused across levels.
void write_level(std::ostream& out, const Texture& m, int layer, const FormatInfo& f,
                 std::unique_ptr<uint8_t[]>& chunk, BcSliceCache* cache) {
  const int nc = m.channel_count();
  if (f.block) {
    std::vector<uint8_t> scratch;
    for (int z = 0; z < m.depth; ++z) {
      const std::vector<uint8_t>& slice = encode_bc_slice(
          cache, scratch, m.texel(0, 0, z, layer), m.width, m.height, nc, *f.block);
      out.write(reinterpret_cast<const char*>(slice.data()), std::streamsize(slice.size()));
    }
    return;
  }
  const size_t texels = size_t(m.width) * size_t(m.height) * size_t(m.depth);
  if (!chunk) chunk.reset(new uint8_t[kChunkTexels * size_t(f.bytes)]);
  const float* src = m.texel(0, 0, 0, layer);
  for (size_t begin = 0; begin < texels && out; begin += kChunkTexels) {
    const size_t end = std::min(texels, begin + kChunkTexels);
    // Each texel's bytes depend on that texel only: any split gives the same bytes.
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, kEncodeGrain),
                      [&](const tbb::blocked_range<size_t>& r) {
                        encode_dds_texels(f.format, src + r.begin() * nc, nc, r.size(),
                                          &chunk[(r.begin() - begin) * size_t(f.bytes)]);
                      });
    out.write(reinterpret_cast<const char*>(chunk.get()),
              std::streamsize((end - begin) * size_t(f.bytes)));
  }
}

// Decodes one mip level of one array slice from `p` into `m` (layer `layer`).
void decode_level(const uint8_t* p, const FormatInfo& f, Texture& m, int layer) {
  const int nc = f.decoded_components;
  const size_t slice_texels = size_t(m.width) * size_t(m.height);
  if (f.block) {
    const size_t slice_bytes = dds_level_bytes(f, m.width, m.height, 1);
    for (int z = 0; z < m.depth; ++z) {
      const std::vector<float> texels = decode_bc(p + z * slice_bytes, m.width, m.height, *f.block);
      std::copy(texels.begin(), texels.end(), m.texel(0, 0, z, layer));
    }
    return;
  }
  float* dst = m.texel(0, 0, 0, layer);
  const size_t texels = slice_texels * size_t(m.depth);
  for (size_t t = 0; t < texels; ++t, p += f.bytes) decode_dds_texel(f.format, p, dst + t * nc);
}

// ---- reading ---------------------------------------------------------------

DdsHeaderInfo parse_header(const std::string& path, const std::vector<uint8_t>& b,
                           uint64_t file_size) {
  if (b.size() < 128)
    throw IoError(fmt::format("{}: expected at least 128 bytes (magic and DDS_HEADER), got {}",
                              path, b.size()));
  if (get_u32(&b[0]) != dds::kMagic)
    throw IoError(fmt::format("{}: expected the magic \"DDS \", got \"{}\"", path,
                              four_cc_string(get_u32(&b[0]))));
  DdsHeaderInfo h;
  h.file_size = file_size;
  uint32_t* fields[] = {&h.size,  &h.flags,        &h.height, &h.width, &h.pitch_or_linear_size,
                        &h.depth, &h.mip_map_count};  // offsets 4..28, in order
  for (int i = 0; i < 7; ++i) *fields[i] = get_u32(&b[4 + 4 * i]);
  for (int i = 0; i < 11; ++i) h.reserved1[i] = get_u32(&b[32 + 4 * i]);
  DdsPixelFormat& pf = h.pixel_format;
  pf.size = get_u32(&b[76]), pf.flags = get_u32(&b[80]), pf.four_cc = get_u32(&b[84]);
  pf.rgb_bit_count = get_u32(&b[88]), pf.r_bit_mask = get_u32(&b[92]);
  pf.g_bit_mask = get_u32(&b[96]), pf.b_bit_mask = get_u32(&b[100]);
  pf.a_bit_mask = get_u32(&b[104]);
  h.caps = get_u32(&b[108]), h.caps2 = get_u32(&b[112]), h.caps3 = get_u32(&b[116]);
  h.caps4 = get_u32(&b[120]), h.reserved2 = get_u32(&b[124]);
  h.has_dx10 = (pf.flags & dds::kDdpfFourCC) && pf.four_cc == dds::kFourCCDx10;
  if (h.has_dx10 && b.size() >= dds::kHeaderBytes) {
    h.dxgi_format = get_u32(&b[128]), h.resource_dimension = get_u32(&b[132]);
    h.misc_flag = get_u32(&b[136]), h.array_size = get_u32(&b[140]);
    h.misc_flags2 = get_u32(&b[144]);
  }
  return h;
}

// Everything read_dds needs from a header, validated.
struct Layout {
  const FormatInfo* format;
  int width, height, depth, layers, levels;  // layers: array slices, or six per cube
  bool cube;
  uint32_t header_bytes;
  uint64_t data_bytes;
  uint64_t decoded_bytes;  // float32 texels of every level and layer
};

// Bounds on what a header may announce (Direct3D 12: D3D12_REQ_TEXTURE2D_U_OR_V_DIMENSION,
// D3D12_REQ_TEXTURE3D_U_V_OR_W_DIMENSION, D3D12_REQ_TEXTURE2D_ARRAY_AXIS_DIMENSION), and on
// the decoded texels, so that a header cannot make the reader allocate more
// than a few GiB even when the file is that long.
constexpr uint32_t kMaxDdsSide = 16384;
constexpr uint32_t kMaxDdsVolumeSide = 2048;
constexpr uint32_t kMaxDdsArraySize = 2048;
constexpr uint64_t kMaxDdsDecodedBytes = uint64_t(4) << 30;

// Header sizes come from the file: they saturate (io/size_math.hpp).
using sizes::kU64Max;
using sizes::mul_saturated;

// The format, the dimension and the array size, from the DX10 header or, in
// a legacy file, from the pixel format and caps2.
struct Described {
  const FormatInfo* format;
  bool volume;
  uint32_t array_size;
  uint32_t header_bytes;
  bool cube = false;  // array_size counts cubes of six faces
};

Described describe_legacy(const std::string& path, const DdsHeaderInfo& h) {
  const DdsPixelFormat& pf = h.pixel_format;
  const FormatInfo* format = find_legacy_format(pf);
  if (!format) {
    std::string legacy;
    for (DdsFormat f : dds_formats())
      if (dds_has_legacy_form(f)) legacy += std::string(legacy.empty() ? "" : ", ") + dxgi_format_name(f);
    throw IoError(fmt::format(
        "{}: expected a DX10 header or the legacy pixel format of one of {}, got {}", path, legacy,
        (pf.flags & dds::kDdpfFourCC)
            ? fmt::format("FourCC \"{}\" ({})", four_cc_string(pf.four_cc), pf.four_cc)
            : fmt::format("flags 0x{:x}, {} bits, masks 0x{:x} 0x{:x} 0x{:x} 0x{:x}", pf.flags,
                          pf.rgb_bit_count, pf.r_bit_mask, pf.g_bit_mask, pf.b_bit_mask,
                          pf.a_bit_mask)));
  }
  if (h.caps2 & dds::kCaps2CubeMap)
    throw IoError(fmt::format("{}: expected no cube map, got caps2 0x{:x}", path, h.caps2));
  return {format, (h.caps2 & dds::kCaps2Volume) != 0, 1, dds::kLegacyHeaderBytes};
}

// A DX10 cube map: a 2D texture, square faces, caps2 naming the cube and
// all six faces (DDS_CUBEMAP_ALLFACES; skybake writes no partial cubes).
void check_cube_header(const std::string& path, const DdsHeaderInfo& h, bool volume) {
  if (volume)
    throw IoError(fmt::format("{}: expected resourceDimension 3 (TEXTURE2D) for a cube map, got 4",
                              path));
  if ((h.caps2 & dds::kCaps2CubeAllFaces) != dds::kCaps2CubeAllFaces)
    throw IoError(fmt::format(
        "{}: expected caps2 with the cube map and all six faces (0x{:x}) for miscFlag "
        "TEXTURECUBE, got 0x{:x}",
        path, dds::kCaps2CubeAllFaces, h.caps2));
  if (h.width != h.height)
    throw IoError(fmt::format("{}: expected square cube faces, got {}x{}", path, h.width,
                              h.height));
}

Described describe(const std::string& path, const DdsHeaderInfo& h) {
  if (h.size != 124)
    throw IoError(fmt::format("{}: expected DDS_HEADER size 124, got {}", path, h.size));
  if (h.pixel_format.size != 32)
    throw IoError(
        fmt::format("{}: expected DDS_PIXELFORMAT size 32, got {}", path, h.pixel_format.size));
  if (!h.has_dx10) return describe_legacy(path, h);
  if (h.file_size < dds::kHeaderBytes)
    throw IoError(
        fmt::format("{}: expected at least {} bytes (magic, DDS_HEADER and "
                    "DDS_HEADER_DXT10), got {}",
                    path, dds::kHeaderBytes, h.file_size));
  const FormatInfo* format = find_format(h.dxgi_format);
  if (!format)
    throw IoError(fmt::format("{}: expected a DXGI format among {}, got {}", path,
                              format_list(true), h.dxgi_format));
  const bool volume = h.resource_dimension == dds::kDimensionTexture3D;
  if (!volume && h.resource_dimension != dds::kDimensionTexture2D)
    throw IoError(
        fmt::format("{}: expected resourceDimension 3 (TEXTURE2D) or 4 (TEXTURE3D), "
                    "got {}",
                    path, h.resource_dimension));
  const bool cube = (h.misc_flag & dds::kMiscTextureCube) != 0;
  if (cube) check_cube_header(path, h, volume);
  else if (h.caps2 & dds::kCaps2CubeMap)
    throw IoError(fmt::format("{}: expected no cube map (miscFlag 0x{:x}), got caps2 0x{:x}", path,
                              h.misc_flag, h.caps2));
  return {format, volume, h.array_size, dds::kHeaderBytes, cube};
}

Layout validate(const std::string& path, const DdsHeaderInfo& h) {
  const Described d = describe(path, h);
  Layout l{};
  l.format = d.format;
  l.header_bytes = d.header_bytes;
  const bool volume = d.volume;
  const uint32_t depth = volume ? h.depth : 1;
  // Direct3D 12's resource limits, which every file skybake writes is within:
  // they bound each header size before anything is computed from it.
  const uint32_t side_limit = volume ? kMaxDdsVolumeSide : kMaxDdsSide;
  const char* const kind = volume ? "a volume" : "a 2D texture";
  const std::pair<const char*, uint32_t> sides[] = {
      {"width", h.width}, {"height", h.height}, {"depth", depth}};
  for (const auto& [field, value] : sides)
    if (value < 1 || value > side_limit)
      throw IoError(fmt::format("{}: expected {} from 1 to {} for {}, got {}", path, field,
                                side_limit, kind, value));
  if (volume && d.array_size != 1)
    throw IoError(fmt::format("{}: expected arraySize 1 for a volume, got {}", path, d.array_size));
  if (d.array_size < 1 || d.array_size > kMaxDdsArraySize)
    throw IoError(fmt::format("{}: expected arraySize from 1 to {}, got {}", path,
                              kMaxDdsArraySize, d.array_size));
  l.width = int(h.width), l.height = int(h.height), l.depth = int(depth);
  l.layers = int(d.array_size) * (d.cube ? 6 : 1);
  l.cube = d.cube;
  // DirectXTex reads mipMapCount even without DDSD_MIPMAPCOUNT; 0 means 1.
  const int full = mip_count(l.width, l.height, l.depth);
  if (h.mip_map_count > uint32_t(full))
    throw IoError(fmt::format("{}: expected mipMapCount at most {} for {}x{}x{}, got {}", path, full,
                              l.width, l.height, l.depth, h.mip_map_count));
  l.levels = std::max(1, int(h.mip_map_count));
  uint64_t per_layer = 0, texels_per_layer = 0;
  for (int i = 0; i < l.levels; ++i) {
    const Shape s = level_shape({l.width, l.height, l.depth}, i);
    // Sides are at most 16384, so these products fit in 64 bits.
    per_layer += dds_level_bytes(*l.format, s.width, s.height, s.depth);
    texels_per_layer += uint64_t(s.width) * uint64_t(s.height) * uint64_t(s.depth);
  }
  l.data_bytes = mul_saturated(per_layer, uint64_t(l.layers));
  const uint64_t decoded =
      mul_saturated(mul_saturated(texels_per_layer, uint64_t(l.layers)),
                    uint64_t(l.format->decoded_components) * sizeof(float));
  l.decoded_bytes = decoded;
  if (decoded > kMaxDdsDecodedBytes)
    throw IoError(fmt::format(
        "{}: expected at most {} GiB of float32 texels (all mip levels and layers), got {} "
        "bytes for {}x{}x{} with arraySize {} and {} mip levels",
        path, kMaxDdsDecodedBytes >> 30, decoded, l.width, l.height, l.depth, l.layers, l.levels));
  const uint64_t got = h.file_size - l.header_bytes;
  if (got != l.data_bytes)
    throw IoError(
        fmt::format("{}: expected {} bytes of pixel data after the {}-byte header, got "
                    "{}{}",
                    path, l.data_bytes, l.header_bytes, got,
                    got < l.data_bytes ? " (truncated file)" : " (trailing bytes)"));
  return l;
}

// The header, then every array slice's levels (write_dds, write_dds_cube).
void write_dds_file(const std::string& path, const MipLevels& mips, const FormatInfo& f,
                    const std::vector<uint8_t>& header, BcSliceCache* cache) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    throw IoError(fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno)));
  out.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
  // Array slices outermost, then mip levels; a level's depth slices are
  // contiguous in both Texture and DDS order, so one loop serves 2D arrays
  // (slice -> mips) and volumes (mip -> slices, with a single "slice").
  std::unique_ptr<uint8_t[]> chunk;
  for (int layer = 0; layer < mips[0]->layers && out; ++layer)
    for (const Texture* m : mips) write_level(out, *m, layer, f, chunk, cache);
  out.close();
  if (!out) {
    const std::string reason = std::strerror(errno);
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: write failed: {}", path, reason));
  }
}

const std::vector<std::string>& channel_names(int components) {
  static const std::vector<std::string> names[] = {
      {"R"}, {"R", "G"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
  return names[components - 1];
}

}  // namespace

const std::vector<DdsFormat>& dds_formats() {
  static const std::vector<DdsFormat> all = [] {
    std::vector<DdsFormat> v;
    for (const FormatInfo& f : dds_format_infos()) v.push_back(f.format);
    return v;
  }();
  return all;
}

const char* dxgi_format_name(DdsFormat format) {
  return info(format).name;
}
int dds_component_count(DdsFormat format) {
  return info(format).components;
}
int dds_bytes_per_texel(DdsFormat format) {
  return info(format).bytes;
}
bool dds_is_block_compressed(DdsFormat format) {
  return info(format).block.has_value();
}
bool dds_has_legacy_form(DdsFormat format) {
  return info(format).legacy.has_value();
}

DdsHeader dds_default_header(DdsFormat format, int layers) {
  switch (format) {
    case DdsFormat::R8G8B8A8_UNORM:
    case DdsFormat::R8_UNORM:
    case DdsFormat::BC1_UNORM:
    case DdsFormat::BC3_UNORM:
    case DdsFormat::BC4_UNORM:
    case DdsFormat::BC5_UNORM:
      return layers > 1 ? DdsHeader::dx10 : DdsHeader::legacy;
    default:
      return DdsHeader::dx10;
  }
}

DdsFormat dds_format_from_name(const std::string& name, const std::string& context) {
  const std::string prefix = "DXGI_FORMAT_";
  const std::string bare =
      name.compare(0, prefix.size(), prefix) == 0 ? name.substr(prefix.size()) : name;
  for (const FormatInfo& f : dds_format_infos())
    if (bare == f.name) return f.format;
  std::vector<std::string> names;
  for (const FormatInfo& f : dds_format_infos()) names.push_back(f.name);
  const std::string* best = same_format_name(bare, names);
  if (!best) best = closest_name(bare, names, 2);
  throw IoError(fmt::format("{}: expected one of {}, got \"{}\"{}", context, format_list(false),
                            name, best ? fmt::format(" (did you mean \"{}\"?)", *best) : ""));
}

std::string four_cc_string(uint32_t four_cc) {
  std::string s(4, '?');
  for (int i = 0; i < 4; ++i) {
    const char c = char((four_cc >> (8 * i)) & 0xFF);
    if (std::isprint((unsigned char)c)) s[i] = c;
  }
  return s;
}

void write_dds(const std::string& path, const std::vector<Texture>& mips, DdsFormat format,
               DdsHeader header_kind, FiniteCheck level0) {
  MipLevels levels;
  for (const Texture& m : mips) levels.push_back(&m);
  write_dds(path, levels, format, header_kind, level0);
}

void write_dds(const std::string& path, const MipLevels& mips, DdsFormat format,
               DdsHeader header_kind, FiniteCheck level0, BcSliceCache* cache) {
  const FormatInfo& f = info(format);
  check_writable(path, mips, f, header_kind, level0);
  write_dds_file(path, mips, f, make_header(mips, f, header_kind), cache);
}

void write_dds_cube(const std::string& path, const MipLevels& mips, DdsFormat format,
                    FiniteCheck level0) {
  const FormatInfo& f = info(format);
  check_writable(path, mips, f, DdsHeader::dx10, level0);
  const Texture& top = *mips[0];
  if (top.depth != 1 || top.width != top.height || top.layers % 6 != 0)
    throw IoError(fmt::format(
        "{}: expected square 2D faces, six per cube, got {}", path, top.shape_string()));
  write_dds_file(path, mips, f, make_header(mips, f, DdsHeader::dx10, true), nullptr);
}

DdsHeaderInfo read_dds_header(const std::string& path) {
  // Only a regular file: a FIFO would block the open, a device never ends.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode))
    throw IoError(fmt::format("{}: expected a regular file", path));
  return parse_header(path, read_bytes(path, dds::kHeaderBytes), uint64_t(st.st_size));
}

DdsImage read_dds(const std::string& path, uint64_t budget) {
  const DdsHeaderInfo h = read_dds_header(path);
  const Layout l = validate(path, h);  // also bounds the allocation by the file size
  // The whole file is read, then decoded into textures of every level.
  check_read_budget(path, sizes::add_saturated(l.decoded_bytes, h.file_size), budget,
                    fmt::format("{}x{}x{} with {} layers and {} mip levels as float32 with {} "
                                "channels, and the file's bytes",
                                l.width, l.height, l.depth, l.layers, l.levels,
                                l.format->decoded_components));
  const std::vector<uint8_t> bytes = read_bytes(path, size_t(h.file_size));
  if (bytes.size() != h.file_size)
    throw IoError(fmt::format("{}: expected {} bytes, got {} (file changed while reading)", path,
                              h.file_size, bytes.size()));
  DdsImage image;
  image.format = l.format->format;
  image.header = h.has_dx10 ? DdsHeader::dx10 : DdsHeader::legacy;
  image.cube = l.cube;
  for (int i = 0; i < l.levels; ++i) {
    const Shape s = level_shape({l.width, l.height, l.depth}, i);
    image.mips.emplace_back(s.width, s.height, s.depth, l.layers,
                            channel_names(l.format->decoded_components));
  }
  const uint8_t* p = bytes.data() + l.header_bytes;
  for (int layer = 0; layer < l.layers; ++layer) {
    for (Texture& m : image.mips) {
      decode_level(p, *l.format, m, layer);
      p += dds_level_bytes(*l.format, m.width, m.height, m.depth);
    }
  }
  return image;
}

}  // namespace skybake

// Our DDS writer and reader: the "DDS " magic, DDS_HEADER (124 bytes), with
// the DX10 header the DDS_HEADER_DXT10 extension (20 bytes), then the pixel
// data.
// References (Microsoft Learn): "DDS_HEADER structure", "DDS_PIXELFORMAT",
// "DDS_HEADER_DXT10 structure", "Programming Guide for DDS", "DXGI_FORMAT",
// "Block Compression (Direct3D 10)"; docs/formats.md "DDS".
//
// Shapes: 2D, 2D array (Texture::layers > 1) and volume (Texture::depth > 1),
// each with or without a mip chain. Data order (Programming Guide for DDS):
// a 2D array stores, for each array slice, all of its mip levels; a volume
// stores, for each mip level, all of its depth slices. Rows are tightly packed
// (pitch = width * bytes per texel), all integers little-endian. Block
// formats (BC1, BC3, BC4, BC5) store each depth slice of each level as rows of
// 4x4 blocks (block_compression.hpp), a level below 4 texels padded to one
// block per axis; dwPitchOrLinearSize then holds the linear size of one slice
// of the top level (blocks across * blocks down * block bytes, as DirectXTex
// writes it) with DDSD_LINEARSIZE instead of DDSD_PITCH.
//
// Channel mapping: the texture's channels fill the format's components in
// order (R, G, B, A). A missing component is written as 0, a missing alpha as
// 1; more channels than the format has is an error (nothing is dropped
// silently). Conversions: UNORM clamps to [0, 1] and stores round(v * 255);
// half rounds to nearest even and clamps finite values beyond +-65504 to
// +-65504, since no Inf may reach a file (docs/architecture.md "Files on
// disk"); R11G11B10 rounds to nearest even, stores negatives as 0 and clamps
// to the largest finite value (65024 for R and G, 64512 for B); block formats
// clamp to [0, 1] and round to 8 bits before encoding.
//
// Headers: DX10 names the DXGI format; its miscFlags2 (alpha
// mode) is DDS_ALPHA_MODE_CUSTOM when the texture's fourth channel fills the
// format's alpha (our alpha channels hold data, a fourth LUT component, not
// coverage), DDS_ALPHA_MODE_OPAQUE when the format has alpha and the texture
// leaves it at 1, DDS_ALPHA_MODE_UNKNOWN for formats without alpha. The
// legacy header (pre-DX10, DdsHeader::legacy) describes the format with a
// FourCC or bit masks instead (dds_format_table.hpp lists them); it has no
// array size, so only single 2D textures and volumes can use it, and
// R11G11B10_FLOAT has no legacy form.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/finite_check.hpp"
#include "core/texture.hpp"
#include "io/read_budget.hpp"
#include "io/block_compression.hpp"

namespace skybake {

// The supported formats; each value is its DXGI_FORMAT code.
enum class DdsFormat : uint32_t {
  R32G32B32A32_FLOAT = 2,
  R16G16B16A16_FLOAT = 10,
  R11G11B10_FLOAT = 26,
  R8G8B8A8_UNORM = 28,
  R8G8_UNORM = 49,
  R16_FLOAT = 54,
  R8_UNORM = 61,
  BC1_UNORM = 71,
  BC3_UNORM = 77,
  BC4_UNORM = 80,
  BC5_UNORM = 83,
};

// Which header describes the format: DDS_HEADER_DXT10 (DXGI code) or the
// pre-DX10 pixel format alone.
enum class DdsHeader { dx10, legacy };

// Every supported format, in the order above.
const std::vector<DdsFormat>& dds_formats();
// "R16G16B16A16_FLOAT" (the DXGI name without the DXGI_FORMAT_ prefix).
const char* dxgi_format_name(DdsFormat format);
// Parses a name as written by dxgi_format_name (the "DXGI_FORMAT_" prefix is
// accepted too). Throws IoError "<context>: expected one of R32G32B32A32_FLOAT,
// ..., got "x"" with a "did you mean" suggestion when one is close.
DdsFormat dds_format_from_name(const std::string& name, const std::string& context = "DDS format");
// Channels the format stores: 4 (RGBA formats, BC3), 3 (R11G11B10, BC1),
// 2 (R8G8, BC5), 1 (R8, R16, BC4).
int dds_component_count(DdsFormat format);
// Bytes per texel: 16, 8, 4, 4, 2, 2, 1; 0 for the block formats.
int dds_bytes_per_texel(DdsFormat format);
// BC1_UNORM .. BC5_UNORM.
bool dds_is_block_compressed(DdsFormat format);
// Whether the format has a pre-DX10 pixel format (all but R11G11B10_FLOAT).
bool dds_has_legacy_form(DdsFormat format);
// The header a file gets when its output does not choose one, as texconv
// (DirectXTex) chooses: legacy for a single texture (2D or volume) in
// R8G8B8A8_UNORM, R8_UNORM (luminance), BC1 (DXT1), BC3 (DXT5), BC4 (ATI1) or
// BC5 (ATI2), the forms that image tools outside engines read; DX10 for the
// float formats, R8G8_UNORM (whose legacy masks leave B empty, which some
// readers do not handle) and 2D arrays (`layers` > 1), which only DX10 can
// describe. docs/formats.md "Which tools read which file" has the measurements.
DdsHeader dds_default_header(DdsFormat format, int layers);

// Writes `mips` (mips[0] full size; level i is max(1, size0 >> i) on every
// axis; all levels share layers and channels; at most a full chain) to exactly
// `path`. Checks everything (shape, chain, channel count, check_finite of
// every level) before the file is opened, so a refused texture creates no
// file; a legacy header for a format without one, or for a 2D array, is such
// a refusal. Throws IoError on a bad input or a failed write. Block formats
// are encoded with tbb::parallel_for (bytes independent of the thread count).
void write_dds(const std::string& path, const std::vector<Texture>& mips, DdsFormat format,
               DdsHeader header = DdsHeader::dx10, FiniteCheck level0 = FiniteCheck::run);
// The same from levels held elsewhere (level 0 need not be copied next to
// the levels built from it).
// A block format's slices go through `cache` when given (block_compression.hpp).
using MipLevels = std::vector<const Texture*>;
void write_dds(const std::string& path, const MipLevels& mips, DdsFormat format,
               DdsHeader header = DdsHeader::dx10, FiniteCheck level0 = FiniteCheck::run,
               BcSliceCache* cache = nullptr);

// Writes a cube map or cube array (Microsoft Learn "Programming Guide for
// DDS", "DDS_HEADER_DXT10"): `mips` as write_dds takes them, square 2D
// faces, layer 6 c + f face f of cube c in the order +X, -X, +Y, -Y, +Z, -Z.
// DX10 header: miscFlag DDS_RESOURCE_MISC_TEXTURECUBE, arraySize the number
// of cubes, caps2 DDSCAPS2_CUBEMAP with all six face flags; the data as a
// 2D array's (each face's levels in turn).
void write_dds_cube(const std::string& path, const MipLevels& mips, DdsFormat format,
                    FiniteCheck level0 = FiniteCheck::run);

struct DdsImage {
  std::vector<Texture> mips;  // decoded float values; channels R, G, B, A as the format has
  DdsFormat format = DdsFormat::R32G32B32A32_FLOAT;
  DdsHeader header = DdsHeader::dx10;
  bool cube = false;  // the layers are cube faces, six per cube (write_dds_cube's order)
};

// Reads a DDS file in one of our formats (2D, 2D array, volume, or with a
// DX10 header a cube map or cube array whose caps2 names all six faces), with a DX10 header or the legacy pixel format of one of our formats
// (FourCC 116, 113, 111, DXT1, DXT5, ATI1 or BC4U, ATI2 or BC5U; RGBA8, R8G8
// or luminance R8 masks). Validates the magic, the structure sizes, the
// dimension, and that the file holds exactly the bytes the header announces
// (a truncated file is an error). Block formats are decoded by decode_bc
// (BC1 gives R, G, B, A).
// `budget`: the most the file's bytes and the decoded float32 levels may take
// together (io/read_budget.hpp).
DdsImage read_dds(const std::string& path, uint64_t budget = kNoReadBudget);

// DDS_PIXELFORMAT, field by field.
struct DdsPixelFormat {
  uint32_t size = 0, flags = 0, four_cc = 0, rgb_bit_count = 0;
  uint32_t r_bit_mask = 0, g_bit_mask = 0, b_bit_mask = 0, a_bit_mask = 0;
};

// Every raw field of DDS_HEADER and (when present) DDS_HEADER_DXT10, for
// `skybake info` and for diagnostics. Nothing is interpreted or defaulted.
struct DdsHeaderInfo {
  uint64_t file_size = 0;
  uint32_t size = 0, flags = 0, height = 0, width = 0, pitch_or_linear_size = 0;
  uint32_t depth = 0, mip_map_count = 0;
  std::array<uint32_t, 11> reserved1{};
  DdsPixelFormat pixel_format;
  uint32_t caps = 0, caps2 = 0, caps3 = 0, caps4 = 0, reserved2 = 0;
  bool has_dx10 = false;  // pixel_format has DDPF_FOURCC and FourCC "DX10"
  uint32_t dxgi_format = 0, resource_dimension = 0, misc_flag = 0, array_size = 0;
  uint32_t misc_flags2 = 0;
};

// Reads the headers only. Throws IoError when the file cannot be read, is
// shorter than its headers or lacks the "DDS " magic.
DdsHeaderInfo read_dds_header(const std::string& path);

// "DX10", "DXT1"; non-printable bytes as '?'.
std::string four_cc_string(uint32_t four_cc);

// Flag values from the Microsoft headers, for callers that print headers.
namespace dds {
constexpr uint32_t kMagic = 0x20534444;  // "DDS " little-endian
constexpr uint32_t kDdsdCaps = 0x1, kDdsdHeight = 0x2, kDdsdWidth = 0x4, kDdsdPitch = 0x8;
constexpr uint32_t kDdsdPixelFormat = 0x1000, kDdsdMipMapCount = 0x20000;
constexpr uint32_t kDdsdLinearSize = 0x80000, kDdsdDepth = 0x800000;
constexpr uint32_t kDdpfFourCC = 0x4;
constexpr uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipMap = 0x400000;
constexpr uint32_t kCaps2Volume = 0x200000, kCaps2CubeMap = 0x200;
constexpr uint32_t kCaps2CubeAllFaces = 0xFE00;  // DDSCAPS2_CUBEMAP | DDS_CUBEMAP_ALLFACES
constexpr uint32_t kFourCCDx10 = 0x30315844;  // "DX10" little-endian
constexpr uint32_t kDimensionTexture2D = 3, kDimensionTexture3D = 4;
constexpr uint32_t kMiscTextureCube = 0x4;
constexpr uint32_t kAlphaModeUnknown = 0, kAlphaModeOpaque = 3, kAlphaModeCustom = 4;
constexpr uint32_t kHeaderBytes = 4 + 124 + 20;  // magic + DDS_HEADER + DDS_HEADER_DXT10
constexpr uint32_t kLegacyHeaderBytes = 4 + 124;  // magic + DDS_HEADER
}  // namespace dds

}  // namespace skybake

// What the DDS writer and reader know about each format (io-internal): its
// DXGI code and name, the channels it stores, bytes per texel or per 4x4
// block, and its pre-DX10 ("legacy") pixel format where it has one
// (Microsoft Learn "DDS_PIXELFORMAT", "Map Direct3D 9 Formats to Direct3D 10";
// docs/formats.md "DDS"). Plus the per-texel conversions of the uncompressed
// formats (dds.hpp says which).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "io/block_compression.hpp"
#include "io/dds.hpp"

namespace skybake {

struct DdsFormatInfo {
  DdsFormat format;
  const char* name;
  int components;          // channels written (at most this many channels are accepted)
  int decoded_components;  // channels read back (BC1 decodes A too)
  int bytes;               // per texel; 0 for block formats
  std::optional<BcFormat> block;
  bool has_alpha;                        // a component the texture's 4th channel goes to
  std::optional<DdsPixelFormat> legacy;  // the pre-DX10 pixel format, if any
};

// Every format, in the order of dds_formats().
const std::vector<DdsFormatInfo>& dds_format_infos();
// nullptr when the code is not one of ours.
const DdsFormatInfo* find_dds_format(uint32_t dxgi);
// Throws Error for a value outside the enum.
const DdsFormatInfo& dds_format_info(DdsFormat format);
// The format whose legacy pixel format `pf` is (FourCC, or flags, bit count
// and masks), nullptr when none. Also accepts the FourCCs "BC4U" and "BC5U".
const DdsFormatInfo* find_legacy_format(const DdsPixelFormat& pf);

// Bytes of one mip level (all its depth slices) of a w x h x d level.
uint64_t dds_level_bytes(const DdsFormatInfo& f, uint64_t w, uint64_t h, uint64_t d);

// One texel of `nc` channels (nc <= components) into an uncompressed format,
// and back into all decoded components.
void encode_dds_texel(DdsFormat format, const float* src, int nc, uint8_t* dst);
// `count` texels in a row, the same bytes as encode_dds_texel on each.
void encode_dds_texels(DdsFormat format, const float* src, int nc, size_t count, uint8_t* dst);
void decode_dds_texel(DdsFormat format, const uint8_t* src, float* dst);

// Pixel-format flags (DDS_PIXELFORMAT.dwFlags).
namespace dds {
constexpr uint32_t kDdpfAlphaPixels = 0x1, kDdpfRgb = 0x40, kDdpfLuminance = 0x20000;
}  // namespace dds

}  // namespace skybake

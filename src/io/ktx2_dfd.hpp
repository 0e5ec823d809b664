// The Data Format Descriptor of a KTX2 file: one Khronos basic descriptor
// block (Khronos Data Format Specification 1.3, "Khronos Basic Data Format
// Descriptor Block"; KTX File Format Specification 2.0, "Data Format
// Descriptor"), built from the vkFormat and parsed back field by field.
//
// Layout, all little-endian 32-bit words:
//   dfdTotalSize
//   vendorId (bits 0..16) | descriptorType (17..31)          = 0 | 0 (Khronos, basic)
//   versionNumber (0..15) | descriptorBlockSize (16..31)     = 2 (1.3) | 24 + 16 * samples
//   colorModel | colorPrimaries << 8 | transferFunction << 16 | flags << 24
//   texelBlockDimension0..3 (one byte each, size - 1)
//   bytesPlane0..3, bytesPlane4..7 (one byte each)
//   per sample, 4 words:
//     bitOffset (0..15) | bitLength - 1 (16..23) | channelType (24..27) | qualifiers (28..31)
//     samplePosition0..3 (one byte each)
//     sampleLower, sampleUpper
//
// What skybake writes (docs/formats.md "KTX2"): transfer function linear,
// primaries BT.709 (what the Khronos reference mapping from vkFormat assumes;
// docs/decisions/dds-files.md), straight alpha (flags 0), sample positions 0.
// Uncompressed formats use the RGBSDA model with one sample per channel:
// float channels are flagged FLOAT | SIGNED with lower -1.0f and upper 1.0f
// (as 32-bit float bit patterns), unorm channels have lower 0 and upper 255.
// Block-compressed formats use their own model (BC1A, BC3, BC4, BC5) with
// 4x4 texel blocks and 64-bit samples, lower 0, upper 0xFFFFFFFF.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace skybake {

// Model, channel and qualifier values of the Data Format Specification (khr_df.h).
namespace dfd {
constexpr uint32_t kVersion13 = 2;
constexpr uint8_t kModelRgbsda = 1, kModelBc1a = 128, kModelBc3 = 130, kModelBc4 = 131,
                  kModelBc5 = 132;
constexpr uint8_t kPrimariesBt709 = 1;
constexpr uint8_t kTransferLinear = 1, kTransferSrgb = 2;
constexpr uint8_t kChannelRed = 0, kChannelGreen = 1, kChannelBlue = 2, kChannelAlpha = 15;
constexpr uint8_t kChannelBc1aAlphaPresent = 1, kChannelBc3Alpha = 15;
constexpr uint8_t kQualifierSigned = 0x4, kQualifierFloat = 0x8;  // the top nibble of channelType
constexpr uint32_t kFloatMinusOne = 0xBF800000u, kFloatOne = 0x3F800000u;
constexpr uint32_t kHeaderBytes = 4 + 24;  // dfdTotalSize + the block's fixed part
constexpr uint32_t kSampleBytes = 16;
}  // namespace dfd

struct DfdSample {
  uint32_t bit_offset = 0;
  uint32_t bit_length = 0;    // the stored value + 1: bits in the sample
  uint32_t channel_type = 0;  // channel id (low nibble) and qualifiers (high nibble), one byte
  std::array<uint8_t, 4> position{};
  uint32_t lower = 0, upper = 0;
  bool operator==(const DfdSample& o) const;
};

struct BasicDfd {
  uint32_t total_size = 0;
  uint32_t vendor_id = 0, descriptor_type = 0, version = 0, block_size = 0;
  uint8_t color_model = 0, color_primaries = 0, transfer_function = 0, flags = 0;
  std::array<uint8_t, 4> texel_block_dimension{};  // stored values: size - 1
  std::array<uint8_t, 8> bytes_plane{};
  std::vector<DfdSample> samples;
};

// The descriptor every KTX2 file skybake writes carries for `vk_format`;
// throws Error for a format skybake does not write.
BasicDfd dfd_for_vk_format(uint32_t vk_format);

// The bytes of `d`, starting with dfdTotalSize (which is recomputed).
std::vector<uint8_t> encode_dfd(const BasicDfd& d);

// Parses a whole DFD (dfdTotalSize first). Throws IoError "<path>: <rule>"
// when the bytes do not hold one basic descriptor block of a consistent size.
BasicDfd parse_dfd(const std::string& path, const uint8_t* bytes, size_t size);

// Why `got` is not the descriptor skybake reads for `vk_format` ("colorModel:
// expected 1 (RGBSDA), got 2"), or "" when it is. Primaries are free (KTX2,
// "Restrictions"), and so is the premultiplied-alpha flag; everything else must
// match the format's definition, and the transfer function must be linear.
std::string dfd_mismatch(const BasicDfd& got, uint32_t vk_format);

}  // namespace skybake

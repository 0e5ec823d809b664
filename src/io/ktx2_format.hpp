// The vkFormats skybake writes into KTX2 files, with what the container needs
// to know of each: components, texel block size and dimensions, typeSize
// (KTX File Format Specification 2.0, "typeSize", "mipPadding").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/block_compression.hpp"

namespace skybake {

// Each value is its VkFormat code (Vulkan specification, "Formats").
enum class Ktx2Format : uint32_t {
  R8_UNORM = 9,
  R8G8_UNORM = 16,
  R8G8B8A8_UNORM = 37,
  R16_SFLOAT = 76,
  R16G16B16A16_SFLOAT = 97,
  R32_SFLOAT = 100,
  R32G32B32A32_SFLOAT = 109,
  BC1_RGB_UNORM_BLOCK = 131,
  BC3_UNORM_BLOCK = 137,
  BC4_UNORM_BLOCK = 139,
  BC5_UNORM_BLOCK = 141,
};

// bc: 4x4 blocks through io/block_compression.hpp (BcFormat in Ktx2FormatInfo::bc).
enum class Ktx2Encoding { float32, half, unorm8, bc };

struct Ktx2FormatInfo {
  Ktx2Format format;
  const char* name;  // the Vulkan name without "VK_FORMAT_"
  int components;    // channels stored per texel (R, G, B, A in order)
  int block_bytes;   // bytes per texel block (a texel when uncompressed)
  int block_width;   // texels per block along x and y (1 when uncompressed)
  int block_height;
  uint32_t type_size;  // KTX2 typeSize: bytes of one component, 1 for block formats
  Ktx2Encoding encoding;
  BcFormat bc = BcFormat::bc1;  // the block format when encoding is bc
};

// Every supported format, in the order of the enum.
const std::vector<Ktx2FormatInfo>& ktx2_formats();
// nullptr when `vk_format` is not one skybake writes.
const Ktx2FormatInfo* find_ktx2_format(uint32_t vk_format);
// Throws Error for a value outside the enum.
const Ktx2FormatInfo& ktx2_format_info(Ktx2Format format);
const char* ktx2_format_name(Ktx2Format format);
// Parses a name as ktx2_format_name writes it ("VK_FORMAT_" prefix accepted).
// Throws IoError "<context>: expected one of R8_UNORM, ..., got "x"" with a
// "did you mean" when one is close.
Ktx2Format ktx2_format_from_name(const std::string& name,
                                 const std::string& context = "KTX2 format");
// "R8_UNORM (9), R8G8_UNORM (16), ..." for messages.
std::string ktx2_format_list(bool with_codes);

// Bytes of one mip level of `layers` array layers of a width x height x depth
// image (whole texel blocks along x and y).
uint64_t ktx2_level_bytes(const Ktx2FormatInfo& f, uint64_t width, uint64_t height, uint64_t depth,
                          uint64_t layers);
// lcm(texel block size, 4): where each level starts when not supercompressed.
uint32_t ktx2_level_alignment(const Ktx2FormatInfo& f);

}  // namespace skybake

// Our KTX2 writer and strict reader (KTX File Format Specification 2.0; the
// Data Format Descriptor in ktx2_dfd.hpp, the formats in ktx2_format.hpp).
//
// File layout, all integers little-endian:
//   identifier (12 bytes) «KTX 20»\r\n\x1A\n
//   header: vkFormat, typeSize, pixelWidth, pixelHeight, pixelDepth,
//           layerCount, faceCount, levelCount, supercompressionScheme (UInt32 each)
//   index: dfdByteOffset, dfdByteLength, kvdByteOffset, kvdByteLength (UInt32),
//          sgdByteOffset, sgdByteLength (UInt64, always 0: no supercompression)
//   level index: levelCount x {byteOffset, byteLength, uncompressedByteLength} (UInt64),
//          level 0 (the largest) first
//   data format descriptor, then key/value data, then zero padding to
//   lcm(texel block size, 4), then the levels smallest first, each starting
//   at a multiple of that alignment. A level holds its layers, each layer its
//   depth slices, each slice its rows, tightly packed (the Texture order).
//
// Shapes: 2D (pixelDepth 0, layerCount 0), 2D array (layerCount = layers when
// Texture::layers > 1) and 3D (pixelDepth = depth when Texture::depth > 1);
// faceCount 1 (6 for cube maps, write_ktx2_cube), levelCount = the levels
// written (>= 1: never "generate mips").
//
// Key/value data, sorted by key as the specification asks:
//   KTXorientation  "rd" (2D, arrays) or "rdi" (3D): the first texel of the
//                   data is the top-left (front) one, as in Vulkan and D3D
//   KTXwriter       "skybake <version>"
//   skybake.channels  JSON array of the texture's channel names (the format
//                     may store more components than the texture has)
//   skybake.<key>   one per Texture::metadata entry, its value as JSON
// Every value is NUL-terminated UTF-8 (docs/formats.md "KTX2").
//
// Channel mapping and conversions as our DDS writer: channels fill R, G, B, A
// in order, a missing component is 0, a missing alpha 1; half clamps to
// +-65504 and rounds to nearest even; unorm8 clamps to [0, 1] and stores
// round(v * 255). Block-compressed formats (BC1 RGB, BC3, BC4, BC5, UNORM)
// encode each 2D slice of a level with encode_bc (io/block_compression.hpp:
// values clamped to [0, 1]); a 3D level is its slices in order (blocks are
// 4x4x1) and a slice whose sides are not multiples of 4 is padded to whole
// blocks. No Inf or NaN reaches a file.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/finite_check.hpp"
#include "core/texture.hpp"
#include "io/read_budget.hpp"
#include "io/ktx2_dfd.hpp"
#include "io/ktx2_format.hpp"

namespace skybake {

namespace ktx2 {
constexpr uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                     0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr uint32_t kHeaderBytes = 12 + 9 * 4 + 4 * 4 + 2 * 8;  // up to the level index: 80
constexpr uint32_t kLevelIndexEntryBytes = 24;
constexpr const char* kMetaPrefix = "skybake.";
}  // namespace ktx2

// Writes `mips` (mips[0] full size; level i is max(1, size0 >> i) on every
// axis; all levels share layers and channels; at most a full chain) to
// exactly `path` in `format`. Checks everything (shape, chain, channel count,
// metadata keys, check_finite of every level) before the file is opened, so a
// refused texture creates no file. Throws IoError on a bad input or a failed
// write; Error on a reserved metadata key ("channels"). Block formats are
// encoded with encode_bc (parallel; bytes independent of the thread count).
void write_ktx2(const std::string& path, const std::vector<Texture>& mips, Ktx2Format format,
                FiniteCheck level0 = FiniteCheck::run);
// The same from levels held elsewhere (as write_dds takes them); a block
// format's slices go through `cache` when given (block_compression.hpp).
using MipLevels = std::vector<const Texture*>;
void write_ktx2(const std::string& path, const MipLevels& mips, Ktx2Format format,
                FiniteCheck level0 = FiniteCheck::run, BcSliceCache* cache = nullptr);

// Writes a cube map or cube array (KTX 2.0 "faceCount", "Level Images"):
// `mips` as write_ktx2 takes them, square 2D faces, layer 6 c + f face f of
// cube c in the order +X, -X, +Y, -Y, +Z, -Z; faceCount 6, layerCount the
// number of cubes (0 for one cube).
void write_ktx2_cube(const std::string& path, const MipLevels& mips, Ktx2Format format,
                     FiniteCheck level0 = FiniteCheck::run);

struct Ktx2LevelIndex {
  uint64_t byte_offset = 0, byte_length = 0, uncompressed_byte_length = 0;
};

// The raw fields of the header, index and level index, nothing interpreted.
struct Ktx2Header {
  uint64_t file_size = 0;
  uint32_t vk_format = 0, type_size = 0, pixel_width = 0, pixel_height = 0, pixel_depth = 0;
  uint32_t layer_count = 0, face_count = 0, level_count = 0, supercompression_scheme = 0;
  uint32_t dfd_byte_offset = 0, dfd_byte_length = 0, kvd_byte_offset = 0, kvd_byte_length = 0;
  uint64_t sgd_byte_offset = 0, sgd_byte_length = 0;
  std::vector<Ktx2LevelIndex> levels;
};

struct Ktx2Image {
  std::vector<Texture> mips;  // decoded; channels and metadata (on mips[0]) from the key/value data
  Ktx2Format format = Ktx2Format::R32G32B32A32_SFLOAT;
  bool cube = false;  // faceCount 6: the layers are faces, six per cube
  Ktx2Header header;
  BasicDfd dfd;
  std::vector<std::pair<std::string, std::string>> key_values;  // in file order, values raw
};

// Reads a KTX2 file in one of our formats, checking everything the
// specification and this header say: identifier, header fields against each
// other, index and level index against the one layout a writer may produce
// (a truncated file, trailing bytes, misplaced levels or non-zero padding are
// errors), the descriptor against the vkFormat, the key/value data's lengths,
// order and padding, KTXorientation (only "rd" and "rdi" are read: others
// would need the rows flipped) and skybake.* values. Reads cube maps (faceCount
// 6, square faces) as six layers per cube. Refuses other face counts, 1D
// textures, 3D arrays, supercompression and "generate mips" (levelCount 0).
// Sizes are bounded before anything is allocated. Throws IoError naming the
// file and the rule.
// `budget`: the most the file's bytes and the decoded float32 levels may take
// together (io/read_budget.hpp).
Ktx2Image read_ktx2(const std::string& path, uint64_t budget = kNoReadBudget);

}  // namespace skybake

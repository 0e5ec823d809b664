// Block compression (BC1, BC3, BC4, BC5; UNORM) of one 2D slice, for DDS and
// KTX2 files. docs/formats.md "Block compression" has the formats, what they
// cost on the shipped presets and why BC6H and BC7 are not offered.
//
// A slice of w x h texels is cut into ceil(w/4) x ceil(h/4) blocks of 4x4
// texels, stored row of blocks by row of blocks (x fastest); a slice smaller
// than a block, or one whose sides are not multiples of 4 (every mip below
// 4 texels), is padded to whole blocks, and the padding texels decode to
// values nobody reads (Microsoft Learn "Block Compression (Direct3D 10)",
// "Virtual size versus physical size"). Block layouts: Khronos Data Format
// Specification 1.3, "S3TC Compressed Texture Image Formats" (BC1 = DXT1,
// BC3 = DXT5) and "RGTC Compressed Texture Image Formats" (BC4, BC5).
//
// The encoder is libsquish, loaded on first use (squish_plugin.hpp); inputs
// are clamped to [0, 1] and rounded to 8 bits first (round(v * 255)), as an
// 8-bit UNORM file would store them. The decoder is our own, written from the
// specification above and independent of libsquish: interpolated values are
// the exact rationals of the specification (thirds for BC1, sevenths and
// fifths for BC4), returned as float without rounding to 8 bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace skybake {

enum class BcFormat {
  bc1,  // RGB, 8 bytes per block: two RGB565 endpoints, 2-bit indices (alpha decodes as 1)
  bc3,  // RGBA, 16 bytes: BC4-style alpha block then a BC1 colour block (always 4 colours)
  bc4,  // R, 8 bytes: two 8-bit endpoints, 3-bit indices
  bc5,  // RG, 16 bytes: two BC4 blocks (R then G)
};

// "BC1", "BC3", "BC4", "BC5".
const char* bc_format_name(BcFormat format);
// Channels the encoder stores: 3, 4, 1, 2.
int bc_channel_count(BcFormat format);
// Channels the decoder returns: 4 (BC1 decodes R, G, B, A), 4, 1, 2.
int bc_decoded_channel_count(BcFormat format);
// Bytes per 4x4 block: 8, 16, 8, 16.
int bc_block_bytes(BcFormat format);
// Bytes of one compressed w x h slice: ceil(w/4) * ceil(h/4) * block bytes
// (at least one block on each axis).
size_t bc_slice_bytes(int width, int height, BcFormat format);
// Bytes of one row of blocks (DDS pitch): max(1, ceil(w/4)) * block bytes.
size_t bc_row_pitch(int width, BcFormat format);

// Compresses one w x h slice. `texels` holds w * h texels of `channels`
// floats each (x fastest), 1 <= channels <= bc_channel_count(format); a
// missing channel is encoded as 0 (RGB) or 1 (alpha). Values are clamped to
// [0, 1]; NaN is a caller error (the writers refuse non-finite values
// first). Rows of blocks run in tbb::parallel_for; each block is encoded on
// its own, so the bytes do not depend on the thread count. Throws IoError
// when the encoder plugin cannot be loaded (the message names every path
// tried), Error on a bad argument.
std::vector<uint8_t> encode_bc(const float* texels, int width, int height, int channels,
                               BcFormat format);

// encode_bc remembered per slice (texels, size, channels, format): the DDS
// and the KTX2 file of one output hold the same blocks of the same levels,
// and encoding is most of their writing, so each slice is encoded once. The
// caller keeps the texels alive and unchanged while the cache lives. Not
// for concurrent use (encode_bc itself runs in parallel).
class BcSliceCache {
 public:
  const std::vector<uint8_t>& encode(const float* texels, int width, int height, int channels,
                                     BcFormat format);
  size_t encoded() const { return slices_.size(); }  // slices encoded so far

 private:
  struct Key {
    const float* texels;
    int width, height, channels;
    BcFormat format;
    bool operator<(const Key& o) const;
  };
  std::map<Key, std::vector<uint8_t>> slices_;
};

// encode_bc through `cache` when there is one.
const std::vector<uint8_t>& encode_bc_slice(BcSliceCache* cache, std::vector<uint8_t>& scratch,
                                            const float* texels, int width, int height,
                                            int channels, BcFormat format);

// Decodes one w x h slice of bc_slice_bytes(w, h, format) bytes at `blocks`
// into w * h texels of bc_decoded_channel_count(format) floats each (x
// fastest); padding texels are dropped. Pure, single-threaded, never throws
// for any bytes (every bit pattern is a valid block).
std::vector<float> decode_bc(const uint8_t* blocks, int width, int height, BcFormat format);

// Decodes one block into 16 texels of bc_decoded_channel_count(format)
// floats (row by row, x fastest).
void decode_bc_block(const uint8_t* block, BcFormat format, float* texels);

}  // namespace skybake

// The BC1, BC3, BC4 and BC5 decoder (block_compression.hpp), written from the
// Khronos Data Format Specification 1.3, "S3TC Compressed Texture Image
// Formats" and "RGTC Compressed Texture Image Formats", and Microsoft Learn
// "Block Compression (Direct3D 10)". All multi-byte fields are little-endian.
#include <algorithm>

#include "io/block_compression.hpp"
#include "io/le_bytes.hpp"

namespace skybake {
namespace {

using le::get_u16;

// RGB565 endpoint as normalized floats: R = red / 31, G = green / 63,
// B = blue / 31 (S3TC: "the 5-bit or 6-bit value is divided by its maximum").
void rgb_from_565(uint16_t c, float* rgb) {
  rgb[0] = float((c >> 11) & 31) / 31.0f;
  rgb[1] = float((c >> 5) & 63) / 63.0f;
  rgb[2] = float(c & 31) / 31.0f;
}

// The BC1 colour block (8 bytes): color0, color1 (RGB565), then 32 bits of
// 2-bit indices, texel i in bits 2i..2i+1. When color0 > color1 (as
// integers), or always for BC3's colour block (`four_colours`), the palette is
// c0, c1, (2 c0 + c1) / 3, (c0 + 2 c1) / 3; otherwise c0, c1, (c0 + c1) / 2
// and transparent black (RGBA 0, 0, 0, 0).
void decode_colour_block(const uint8_t* block, bool four_colours, float* out, int stride) {
  const uint16_t c0 = get_u16(block), c1 = get_u16(block + 2);
  float palette[4][4] = {};
  rgb_from_565(c0, palette[0]);
  rgb_from_565(c1, palette[1]);
  const bool opaque_mode = four_colours || c0 > c1;
  for (int c = 0; c < 3; ++c) {
    const float a = palette[0][c], b = palette[1][c];
    if (opaque_mode) {
      palette[2][c] = (2.0f * a + b) / 3.0f;
      palette[3][c] = (a + 2.0f * b) / 3.0f;
    } else {
      palette[2][c] = (a + b) / 2.0f;
      palette[3][c] = 0.0f;
    }
  }
  palette[0][3] = palette[1][3] = palette[2][3] = 1.0f;
  palette[3][3] = opaque_mode ? 1.0f : 0.0f;
  const uint32_t bits = uint32_t(get_u16(block + 4)) | uint32_t(get_u16(block + 6)) << 16;
  for (int i = 0; i < 16; ++i) {
    const float* p = palette[(bits >> (2 * i)) & 3];
    std::copy(p, p + 4, out + i * stride);
  }
}

// The BC4 block (8 bytes), also BC3's alpha block and each half of BC5:
// red0, red1 (8-bit UNORM), then 48 bits of 3-bit indices, texel i in bits
// 3i..3i+2. Palette: when red0 > red1, red0, red1 and (k red0 + (7-k) red1)/7
// for the six weights k = 6..1; otherwise red0, red1, (k red0 + (5-k) red1)/5
// for k = 4..1, then 0 and 1 (RGTC, "BC4 unsigned").
void decode_single_channel_block(const uint8_t* block, float* out, int stride) {
  const float r0 = block[0] / 255.0f, r1 = block[1] / 255.0f;
  float palette[8];
  palette[0] = r0;
  palette[1] = r1;
  if (block[0] > block[1]) {
    for (int k = 6; k >= 1; --k) palette[8 - k] = (float(k) * r0 + float(7 - k) * r1) / 7.0f;
  } else {
    for (int k = 4; k >= 1; --k) palette[6 - k] = (float(k) * r0 + float(5 - k) * r1) / 5.0f;
    palette[6] = 0.0f;
    palette[7] = 1.0f;
  }
  uint64_t bits = 0;
  for (int i = 0; i < 6; ++i) bits |= uint64_t(block[2 + i]) << (8 * i);
  for (int i = 0; i < 16; ++i) out[i * stride] = palette[(bits >> (3 * i)) & 7];
}

}  // namespace

void decode_bc_block(const uint8_t* block, BcFormat format, float* texels) {
  switch (format) {
    case BcFormat::bc1:
      decode_colour_block(block, false, texels, 4);
      break;
    case BcFormat::bc3:
      decode_colour_block(block + 8, true, texels, 4);
      decode_single_channel_block(block, texels + 3, 4);  // alpha comes first
      break;
    case BcFormat::bc4:
      decode_single_channel_block(block, texels, 1);
      break;
    case BcFormat::bc5:
      decode_single_channel_block(block, texels, 2);
      decode_single_channel_block(block + 8, texels + 1, 2);
      break;
  }
}

std::vector<float> decode_bc(const uint8_t* blocks, int width, int height, BcFormat format) {
  const int nc = bc_decoded_channel_count(format);
  const int bytes = bc_block_bytes(format);
  const int blocks_x = std::max(1, (width + 3) / 4), blocks_y = std::max(1, (height + 3) / 4);
  std::vector<float> out(size_t(width) * size_t(height) * size_t(nc));
  float texels[16 * 4];
  for (int by = 0; by < blocks_y; ++by) {
    for (int bx = 0; bx < blocks_x; ++bx) {
      decode_bc_block(blocks + (size_t(by) * blocks_x + bx) * bytes, format, texels);
      for (int j = 0; j < 4 && 4 * by + j < height; ++j)
        for (int i = 0; i < 4 && 4 * bx + i < width; ++i) {
          const float* src = texels + (4 * j + i) * nc;
          std::copy(src, src + nc,
                    out.data() + ((size_t(4 * by + j) * width) + size_t(4 * bx + i)) * nc);
        }
    }
  }
  return out;
}

}  // namespace skybake

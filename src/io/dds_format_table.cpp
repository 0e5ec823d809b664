// The DDS format table and texel conversions (dds_format_table.hpp).
#include "io/dds_format_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/half.hpp"
#include "io/le_bytes.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace skybake {
namespace {

constexpr uint32_t four_cc(const char (&s)[5]) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}

// A legacy pixel format given by a FourCC (a D3DFMT code for the float
// formats, e.g. 113 = D3DFMT_A16B16G16R16F, stored as the FourCC's integer).
constexpr DdsPixelFormat fourcc_format(uint32_t code) {
  return {32, dds::kDdpfFourCC, code, 0, 0, 0, 0, 0};
}
// A legacy pixel format given by flags, bit count and masks.
constexpr DdsPixelFormat mask_format(uint32_t flags, uint32_t bits, uint32_t r, uint32_t g,
                                     uint32_t b, uint32_t a) {
  return {32, flags, 0, bits, r, g, b, a};
}

// Legacy forms: D3DFMT_A32B32G32R32F (116), D3DFMT_A16B16G16R16F (113) and
// D3DFMT_R16F (111) by FourCC; RGBA8 as DDPF_RGB | DDPF_ALPHAPIXELS with byte
// masks R, G, B, A from the low byte up; R8G8 as 16-bit DDPF_RGB with masks R
// 0xff, G 0xff00; R8 as DDPF_LUMINANCE; the block formats by their FourCCs
// DXT1, DXT5, ATI1, ATI2. R11G11B10_FLOAT has none.
const std::vector<DdsFormatInfo> kFormats = {
    {DdsFormat::R32G32B32A32_FLOAT, "R32G32B32A32_FLOAT", 4, 4, 16, std::nullopt, true,
     fourcc_format(116)},
    {DdsFormat::R16G16B16A16_FLOAT, "R16G16B16A16_FLOAT", 4, 4, 8, std::nullopt, true,
     fourcc_format(113)},
    {DdsFormat::R11G11B10_FLOAT, "R11G11B10_FLOAT", 3, 3, 4, std::nullopt, false, std::nullopt},
    {DdsFormat::R8G8B8A8_UNORM, "R8G8B8A8_UNORM", 4, 4, 4, std::nullopt, true,
     mask_format(dds::kDdpfRgb | dds::kDdpfAlphaPixels, 32, 0xff, 0xff00, 0xff0000, 0xff000000)},
    {DdsFormat::R8G8_UNORM, "R8G8_UNORM", 2, 2, 2, std::nullopt, false,
     mask_format(dds::kDdpfRgb, 16, 0xff, 0xff00, 0, 0)},
    {DdsFormat::R16_FLOAT, "R16_FLOAT", 1, 1, 2, std::nullopt, false, fourcc_format(111)},
    {DdsFormat::R8_UNORM, "R8_UNORM", 1, 1, 1, std::nullopt, false,
     mask_format(dds::kDdpfLuminance, 8, 0xff, 0, 0, 0)},
    {DdsFormat::BC1_UNORM, "BC1_UNORM", 3, 4, 0, BcFormat::bc1, false,
     fourcc_format(four_cc("DXT1"))},
    {DdsFormat::BC3_UNORM, "BC3_UNORM", 4, 4, 0, BcFormat::bc3, true,
     fourcc_format(four_cc("DXT5"))},
    {DdsFormat::BC4_UNORM, "BC4_UNORM", 1, 1, 0, BcFormat::bc4, false,
     fourcc_format(four_cc("ATI1"))},
    {DdsFormat::BC5_UNORM, "BC5_UNORM", 2, 2, 0, BcFormat::bc5, false,
     fourcc_format(four_cc("ATI2"))},
};

bool same_masks(const DdsPixelFormat& a, const DdsPixelFormat& b) {
  return a.rgb_bit_count == b.rgb_bit_count && a.r_bit_mask == b.r_bit_mask &&
         a.g_bit_mask == b.g_bit_mask && a.b_bit_mask == b.b_bit_mask &&
         a.a_bit_mask == b.a_bit_mask;
}

// ---- little-endian texels --------------------------------------------------

using le::get_f32;
using le::get_u16;
using le::get_u32;
using le::put_f32;
using le::put_u16;
using le::put_u32;
// lround of x in [0, 255] (halves away from zero), without the library
// call: x - trunc(x) is exact for such floats, so the comparison decides.
uint8_t unorm8_from_float(float v) {
  const float x = std::clamp(v, 0.0f, 1.0f) * 255.0f;
  const int i = int(x);
  return uint8_t(i + (x - float(i) >= 0.5f ? 1 : 0));
}
// unorm8_from_float 16 values at a time while 16 remain; returns how many
// it did. The same IEEE operations lane by lane: max/min clamp (the values
// are finite; a -0 clamps to +0, which also gives byte 0), the product,
// truncation, the exact difference and its comparison with 0.5; the packs
// saturate nothing (each value is in [0, 255]).
size_t unorm8_from_floats(const float* src, size_t n, uint8_t* dst) {
  size_t i = 0;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), scale = _mm_set1_ps(255.0f);
  const __m128 half = _mm_set1_ps(0.5f);
  const __m128i inc = _mm_set1_epi32(1);
  auto quad = [&](const float* p) {
    const __m128 x = _mm_mul_ps(_mm_min_ps(_mm_max_ps(_mm_loadu_ps(p), zero), one), scale);
    const __m128i t = _mm_cvttps_epi32(x);
    const __m128 up = _mm_cmpge_ps(_mm_sub_ps(x, _mm_cvtepi32_ps(t)), half);
    return _mm_add_epi32(t, _mm_and_si128(_mm_castps_si128(up), inc));
  };
  for (; i + 16 <= n; i += 16) {
    const __m128i lo = _mm_packs_epi32(quad(src + i), quad(src + i + 4));
    const __m128i hi = _mm_packs_epi32(quad(src + i + 8), quad(src + i + 12));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + i), _mm_packus_epi16(lo, hi));
  }
#else
  (void)src, (void)dst, (void)n;
#endif
  return i;
}

uint16_t half_saturated(float v) {
  return half_from_float(std::clamp(v, -kHalfMax, kHalfMax));
}

}  // namespace

const std::vector<DdsFormatInfo>& dds_format_infos() {
  return kFormats;
}

const DdsFormatInfo* find_dds_format(uint32_t dxgi) {
  for (const DdsFormatInfo& f : kFormats)
    if (uint32_t(f.format) == dxgi) return &f;
  return nullptr;
}

const DdsFormatInfo& dds_format_info(DdsFormat format) {
  const DdsFormatInfo* f = find_dds_format(uint32_t(format));
  if (!f) throw Error(fmt::format("unknown DdsFormat value {}", uint32_t(format)));
  return *f;
}

const DdsFormatInfo* find_legacy_format(const DdsPixelFormat& pf) {
  uint32_t code = pf.four_cc;
  if (pf.flags & dds::kDdpfFourCC) {
    if (code == four_cc("BC4U")) code = four_cc("ATI1");
    if (code == four_cc("BC5U")) code = four_cc("ATI2");
    for (const DdsFormatInfo& f : kFormats)
      if (f.legacy && (f.legacy->flags & dds::kDdpfFourCC) && f.legacy->four_cc == code) return &f;
    return nullptr;
  }
  const uint32_t kind = pf.flags & (dds::kDdpfRgb | dds::kDdpfLuminance | dds::kDdpfAlphaPixels);
  for (const DdsFormatInfo& f : kFormats)
    if (f.legacy && !(f.legacy->flags & dds::kDdpfFourCC) && f.legacy->flags == kind &&
        same_masks(*f.legacy, pf))
      return &f;
  return nullptr;
}

uint64_t dds_level_bytes(const DdsFormatInfo& f, uint64_t w, uint64_t h, uint64_t d) {
  if (f.block)
    return ((w + 3) / 4) * ((h + 3) / 4) * uint64_t(bc_block_bytes(*f.block)) * d;
  return w * h * d * uint64_t(f.bytes);
}

void encode_dds_texel(DdsFormat format, const float* src, int nc, uint8_t* dst) {
  float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // missing components 0, missing alpha 1
  std::copy(src, src + nc, v);
  switch (format) {
    case DdsFormat::R32G32B32A32_FLOAT:
      for (int c = 0; c < 4; ++c) put_f32(dst + 4 * c, v[c]);
      break;
    case DdsFormat::R16G16B16A16_FLOAT:
      for (int c = 0; c < 4; ++c) put_u16(dst + 2 * c, half_saturated(v[c]));
      break;
    case DdsFormat::R11G11B10_FLOAT:
      put_u32(dst, r11g11b10_from_rgb(std::min(v[0], kFloat11Max), std::min(v[1], kFloat11Max),
                                      std::min(v[2], kFloat10Max)));
      break;
    case DdsFormat::R8G8B8A8_UNORM:
      for (int c = 0; c < 4; ++c) dst[c] = unorm8_from_float(v[c]);
      break;
    case DdsFormat::R8G8_UNORM:
      for (int c = 0; c < 2; ++c) dst[c] = unorm8_from_float(v[c]);
      break;
    case DdsFormat::R16_FLOAT:
      put_u16(dst, half_saturated(v[0]));
      break;
    case DdsFormat::R8_UNORM:
      dst[0] = unorm8_from_float(v[0]);
      break;
    default:
      throw Error(fmt::format("encode_dds_texel: {} is a block format", uint32_t(format)));
  }
}

void encode_dds_texels(DdsFormat format, const float* src, int nc, size_t count, uint8_t* dst) {
  // The 8-bit formats of the cloud textures, channels filling the texel: one
  // loop over the values, no per-texel dispatch.
  const bool unorm8 = (format == DdsFormat::R8G8B8A8_UNORM && nc == 4) ||
                      (format == DdsFormat::R8G8_UNORM && nc == 2) ||
                      (format == DdsFormat::R8_UNORM && nc == 1);
  if (unorm8) {
    const size_t n = count * size_t(nc);
    const size_t done = unorm8_from_floats(src, n, dst);
    for (size_t i = done; i < n; ++i) dst[i] = unorm8_from_float(src[i]);
    return;
  }
  const size_t bytes = size_t(dds_format_info(format).bytes);
  for (size_t t = 0; t < count; ++t) encode_dds_texel(format, src + t * nc, nc, dst + t * bytes);
}

void decode_dds_texel(DdsFormat format, const uint8_t* src, float* dst) {
  switch (format) {
    case DdsFormat::R32G32B32A32_FLOAT:
      for (int c = 0; c < 4; ++c) dst[c] = get_f32(src + 4 * c);
      break;
    case DdsFormat::R16G16B16A16_FLOAT:
      for (int c = 0; c < 4; ++c) dst[c] = float_from_half(get_u16(src + 2 * c));
      break;
    case DdsFormat::R11G11B10_FLOAT: {
      const Rgb rgb = rgb_from_r11g11b10(get_u32(src));
      dst[0] = rgb.r, dst[1] = rgb.g, dst[2] = rgb.b;
      break;
    }
    case DdsFormat::R8G8B8A8_UNORM:
      for (int c = 0; c < 4; ++c) dst[c] = src[c] / 255.0f;
      break;
    case DdsFormat::R8G8_UNORM:
      for (int c = 0; c < 2; ++c) dst[c] = src[c] / 255.0f;
      break;
    case DdsFormat::R16_FLOAT:
      dst[0] = float_from_half(get_u16(src));
      break;
    case DdsFormat::R8_UNORM:
      dst[0] = src[0] / 255.0f;
      break;
    default:
      throw Error(fmt::format("decode_dds_texel: {} is a block format", uint32_t(format)));
  }
}

}  // namespace skybake

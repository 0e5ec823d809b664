// Data Format Descriptors of KTX2 files (ktx2_dfd.hpp for the layout).
#include "io/ktx2_dfd.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "io/ktx2_format.hpp"
#include "io/le_bytes.hpp"

namespace skybake {

namespace {

constexpr uint8_t kRgbaChannels[4] = {dfd::kChannelRed, dfd::kChannelGreen, dfd::kChannelBlue,
                                      dfd::kChannelAlpha};

// RGBSDA, one sample per component (Data Format Specification 1.3,
// "RGBSDA"; the KTX-Software reference mapping for little-endian unpacked formats).
BasicDfd uncompressed(const Ktx2FormatInfo& f) {
  BasicDfd d;
  d.color_model = dfd::kModelRgbsda;
  d.bytes_plane[0] = uint8_t(f.block_bytes);
  const uint32_t bits = f.type_size * 8;
  for (int c = 0; c < f.components; ++c) {
    DfdSample s;
    s.bit_offset = uint32_t(c) * bits;
    s.bit_length = bits;
    s.channel_type = kRgbaChannels[c];
    if (f.encoding == Ktx2Encoding::unorm8) {
      s.lower = 0;
      s.upper = (1u << bits) - 1u;
    } else {
      s.channel_type |= uint32_t(dfd::kQualifierFloat | dfd::kQualifierSigned) << 4;
      s.lower = dfd::kFloatMinusOne;
      s.upper = dfd::kFloatOne;
    }
    d.samples.push_back(s);
  }
  return d;
}

// The block-compressed models (Data Format Specification 1.3, "BC1A",
// "BC3", "BC4", "BC5"): one 64-bit sample per independent half of a block,
// bounds 0 and 0xFFFFFFFF (UNORM).
BasicDfd block_compressed(const Ktx2FormatInfo& f) {
  BasicDfd d;
  d.bytes_plane[0] = uint8_t(f.block_bytes);
  const auto half = [&d](uint8_t channel, uint32_t bit_offset) {
    DfdSample s;
    s.bit_offset = bit_offset;
    s.bit_length = 64;
    s.channel_type = channel;
    s.lower = 0;
    s.upper = 0xFFFFFFFFu;
    d.samples.push_back(s);
  };
  switch (f.bc) {
    case BcFormat::bc1:
      d.color_model = dfd::kModelBc1a;
      half(dfd::kChannelRed, 0);  // KHR_DF_CHANNEL_BC1A_COLOR: no alpha
      break;
    case BcFormat::bc3:
      d.color_model = dfd::kModelBc3;
      half(dfd::kChannelBc3Alpha, 0);  // the alpha block, then the colour block
      half(dfd::kChannelRed, 64);
      break;
    case BcFormat::bc4:
      d.color_model = dfd::kModelBc4;
      half(dfd::kChannelRed, 0);  // KHR_DF_CHANNEL_BC4_DATA
      break;
    case BcFormat::bc5:
      d.color_model = dfd::kModelBc5;
      half(dfd::kChannelRed, 0);
      half(dfd::kChannelGreen, 64);
      break;
  }
  return d;
}

const char* model_name(uint8_t model) {
  switch (model) {
    case dfd::kModelRgbsda:
      return "RGBSDA";
    case dfd::kModelBc1a:
      return "BC1A";
    case dfd::kModelBc3:
      return "BC3";
    case dfd::kModelBc4:
      return "BC4";
    case dfd::kModelBc5:
      return "BC5";
    default:
      return "unknown";
  }
}

std::string sample_text(const DfdSample& s) {
  return fmt::format(
      "{{bitOffset {}, bitLength {}, channelType 0x{:02x}, position [{}, {}, {}, {}], lower "
      "0x{:08x}, upper 0x{:08x}}}",
      s.bit_offset, s.bit_length, s.channel_type, s.position[0], s.position[1], s.position[2],
      s.position[3], s.lower, s.upper);
}

}  // namespace

bool DfdSample::operator==(const DfdSample& o) const {
  return bit_offset == o.bit_offset && bit_length == o.bit_length &&
         channel_type == o.channel_type && position == o.position && lower == o.lower &&
         upper == o.upper;
}

BasicDfd dfd_for_vk_format(uint32_t vk_format) {
  const Ktx2FormatInfo* f = find_ktx2_format(vk_format);
  if (!f) throw Error(fmt::format("no data format descriptor for vkFormat {}", vk_format));
  BasicDfd d = f->encoding == Ktx2Encoding::bc ? block_compressed(*f) : uncompressed(*f);
  d.vendor_id = 0;
  d.descriptor_type = 0;
  d.version = dfd::kVersion13;
  d.color_primaries = dfd::kPrimariesBt709;
  d.transfer_function = dfd::kTransferLinear;
  d.flags = 0;  // straight alpha: our alpha channels hold data, not coverage
  d.texel_block_dimension = {uint8_t(f->block_width - 1), uint8_t(f->block_height - 1), 0, 0};
  d.block_size = 24 + dfd::kSampleBytes * uint32_t(d.samples.size());
  d.total_size = 4 + d.block_size;
  return d;
}

std::vector<uint8_t> encode_dfd(const BasicDfd& d) {
  const uint32_t block_size = 24 + dfd::kSampleBytes * uint32_t(d.samples.size());
  std::vector<uint8_t> b(4 + block_size, 0);
  le::put_u32(&b[0], 4 + block_size);
  le::put_u32(&b[4], (d.vendor_id & 0x1FFFFu) | d.descriptor_type << 17);
  le::put_u32(&b[8], (d.version & 0xFFFFu) | block_size << 16);
  b[12] = d.color_model, b[13] = d.color_primaries, b[14] = d.transfer_function;
  b[15] = d.flags;
  for (int i = 0; i < 4; ++i) b[16 + i] = d.texel_block_dimension[i];
  for (int i = 0; i < 8; ++i) b[20 + i] = d.bytes_plane[i];
  for (size_t i = 0; i < d.samples.size(); ++i) {
    const DfdSample& s = d.samples[i];
    uint8_t* p = &b[28 + dfd::kSampleBytes * i];
    le::put_u32(p, (s.bit_offset & 0xFFFFu) | ((s.bit_length - 1) & 0xFFu) << 16 |
                       (s.channel_type & 0xFFu) << 24);
    for (int k = 0; k < 4; ++k) p[4 + k] = s.position[k];
    le::put_u32(p + 8, s.lower);
    le::put_u32(p + 12, s.upper);
  }
  return b;
}

BasicDfd parse_dfd(const std::string& path, const uint8_t* b, size_t size) {
  if (size < dfd::kHeaderBytes)
    throw IoError(fmt::format("{}: expected a data format descriptor of at least {} bytes, got {}",
                              path, dfd::kHeaderBytes, size));
  BasicDfd d;
  d.total_size = le::get_u32(b);
  if (d.total_size != size)
    throw IoError(fmt::format("{}: expected dfdTotalSize equal to dfdByteLength {}, got {}", path,
                              size, d.total_size));
  const uint32_t w1 = le::get_u32(b + 4), w2 = le::get_u32(b + 8);
  d.vendor_id = w1 & 0x1FFFFu, d.descriptor_type = w1 >> 17;
  d.version = w2 & 0xFFFFu, d.block_size = w2 >> 16;
  if (d.vendor_id != 0 || d.descriptor_type != 0)
    throw IoError(fmt::format(
        "{}: expected a Khronos basic descriptor block (vendorId 0, descriptorType 0), got "
        "vendorId {}, descriptorType {}",
        path, d.vendor_id, d.descriptor_type));
  if (d.block_size < 24 || (d.block_size - 24) % dfd::kSampleBytes != 0 ||
      4 + uint64_t(d.block_size) != size)
    throw IoError(fmt::format(
        "{}: expected one descriptor block of 24 + 16 * samples bytes filling the {}-byte "
        "descriptor, got descriptorBlockSize {}",
        path, size, d.block_size));
  d.color_model = b[12], d.color_primaries = b[13], d.transfer_function = b[14], d.flags = b[15];
  for (int i = 0; i < 4; ++i) d.texel_block_dimension[i] = b[16 + i];
  for (int i = 0; i < 8; ++i) d.bytes_plane[i] = b[20 + i];
  for (uint32_t i = 0; i < (d.block_size - 24) / dfd::kSampleBytes; ++i) {
    const uint8_t* p = b + 28 + dfd::kSampleBytes * i;
    const uint32_t w = le::get_u32(p);
    DfdSample s;
    s.bit_offset = w & 0xFFFFu;
    s.bit_length = ((w >> 16) & 0xFFu) + 1;
    s.channel_type = w >> 24;
    for (int k = 0; k < 4; ++k) s.position[k] = p[4 + k];
    s.lower = le::get_u32(p + 8);
    s.upper = le::get_u32(p + 12);
    d.samples.push_back(s);
  }
  return d;
}

std::string dfd_mismatch(const BasicDfd& got, uint32_t vk_format) {
  const BasicDfd want = dfd_for_vk_format(vk_format);
  if (got.version != want.version)
    return fmt::format("versionNumber: expected {} (1.3), got {}", want.version, got.version);
  if (got.color_model != want.color_model)
    return fmt::format("colorModel: expected {} ({}), got {} ({})", want.color_model,
                       model_name(want.color_model), got.color_model, model_name(got.color_model));
  if (got.transfer_function != dfd::kTransferLinear)
    return fmt::format("transferFunction: expected {} (linear), got {}", dfd::kTransferLinear,
                       got.transfer_function);
  if (got.flags > 1)
    return fmt::format("flags: expected 0 (straight alpha) or 1 (premultiplied), got {}",
                       got.flags);
  if (got.texel_block_dimension != want.texel_block_dimension)
    return fmt::format("texelBlockDimension: expected [{}], got [{}]",
                       fmt::join(want.texel_block_dimension, ", "),
                       fmt::join(got.texel_block_dimension, ", "));
  if (got.bytes_plane != want.bytes_plane)
    return fmt::format("bytesPlane: expected [{}], got [{}]", fmt::join(want.bytes_plane, ", "),
                       fmt::join(got.bytes_plane, ", "));
  if (got.samples.size() != want.samples.size())
    return fmt::format("expected {} samples, got {}", want.samples.size(), got.samples.size());
  for (size_t i = 0; i < want.samples.size(); ++i)
    if (!(got.samples[i] == want.samples[i]))
      return fmt::format("sample {}: expected {}, got {}", i, sample_text(want.samples[i]),
                         sample_text(got.samples[i]));
  return "";
}

}  // namespace skybake

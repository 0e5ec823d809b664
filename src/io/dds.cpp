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

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "core/half.hpp"
#include "core/mip_chain.hpp"
#include "core/suggest.hpp"

namespace skybake {
namespace {

struct FormatInfo {
  DdsFormat format;
  const char* name;
  int components;
  int bytes;
};

constexpr FormatInfo kFormats[] = {
    {DdsFormat::R32G32B32A32_FLOAT, "R32G32B32A32_FLOAT", 4, 16},
    {DdsFormat::R16G16B16A16_FLOAT, "R16G16B16A16_FLOAT", 4, 8},
    {DdsFormat::R11G11B10_FLOAT, "R11G11B10_FLOAT", 3, 4},
    {DdsFormat::R8G8B8A8_UNORM, "R8G8B8A8_UNORM", 4, 4},
    {DdsFormat::R16_FLOAT, "R16_FLOAT", 1, 2},
    {DdsFormat::R8_UNORM, "R8_UNORM", 1, 1},
};

const FormatInfo* find_format(uint32_t dxgi) {
  for (const FormatInfo& f : kFormats)
    if (uint32_t(f.format) == dxgi) return &f;
  return nullptr;
}

const FormatInfo& info(DdsFormat format) {
  const FormatInfo* f = find_format(uint32_t(format));
  if (!f) throw Error(fmt::format("unknown DdsFormat value {}", uint32_t(format)));
  return *f;
}

std::string format_list(bool with_codes) {
  std::string s;
  for (const FormatInfo& f : kFormats) {
    if (!s.empty()) s += ", ";
    s += with_codes ? fmt::format("{} ({})", f.name, uint32_t(f.format)) : f.name;
  }
  return s;
}

// ---- little-endian bytes -------------------------------------------------

void put_u32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
void put_u16(uint8_t* p, uint16_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}
uint32_t get_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint16_t get_u16(const uint8_t* p) {
  return uint16_t(p[0] | p[1] << 8);
}
void put_f32(uint8_t* p, float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  put_u32(p, u);
}
float get_f32(const uint8_t* p) {
  const uint32_t u = get_u32(p);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

// ---- texel conversion ------------------------------------------------------

uint8_t unorm8_from_float(float v) {
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}
uint16_t half_saturated(float v) {
  return half_from_float(std::clamp(v, -kHalfMax, kHalfMax));
}

// Encodes one texel of `nc` channels (nc <= components of the format).
void encode_texel(DdsFormat format, const float* src, int nc, uint8_t* dst) {
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
    case DdsFormat::R16_FLOAT:
      put_u16(dst, half_saturated(v[0]));
      break;
    case DdsFormat::R8_UNORM:
      dst[0] = unorm8_from_float(v[0]);
      break;
  }
}

// Decodes one texel into all components of the format.
void decode_texel(DdsFormat format, const uint8_t* src, float* dst) {
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
    case DdsFormat::R16_FLOAT:
      dst[0] = float_from_half(get_u16(src));
      break;
    case DdsFormat::R8_UNORM:
      dst[0] = src[0] / 255.0f;
      break;
  }
}

// ---- shapes ----------------------------------------------------------------

struct Shape {
  int width, height, depth;
};

Shape level_shape(Shape top, int level) {
  return {std::max(1, top.width >> level), std::max(1, top.height >> level),
          std::max(1, top.depth >> level)};
}

// Refuses anything that would not make a valid DDS file, before any I/O.
void check_writable(const std::string& path, const std::vector<Texture>& mips,
                    const FormatInfo& format) {
  if (mips.empty()) throw IoError(path + ": expected at least one mip level, got none");
  const Texture& top = mips[0];
  if (top.width < 1 || top.height < 1 || top.depth < 1 || top.layers < 1)
    throw IoError(fmt::format("{}: expected a non-empty texture, got {}x{}x{} with {} layers", path,
                              top.width, top.height, top.depth, top.layers));
  if (top.depth > 1 && top.layers > 1)
    throw IoError(
        fmt::format("{}: expected a volume or a 2D array (DDS has no volume arrays), "
                    "got {}",
                    path, top.shape_string()));
  if (top.channel_count() < 1 || top.channel_count() > format.components)
    throw IoError(fmt::format("{}: expected 1 to {} channels for {}, got {}", path,
                              format.components, format.name, top.channel_count()));
  const int full = mip_count(top.width, top.height, top.depth);
  if (int(mips.size()) > full)
    throw IoError(fmt::format("{}: expected at most {} mip levels for {}, got {}", path, full,
                              top.shape_string(), mips.size()));
  for (size_t i = 0; i < mips.size(); ++i) {
    const Texture& m = mips[i];
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
    check_finite(m, i == 0 ? path : fmt::format("{}: mip {}", path, i));
  }
}

std::vector<uint8_t> make_header(const std::vector<Texture>& mips, const FormatInfo& format) {
  const Texture& top = mips[0];
  const bool volume = top.depth > 1;
  const bool has_mips = mips.size() > 1;
  std::vector<uint8_t> h(dds::kHeaderBytes, 0);
  uint32_t flags =
      dds::kDdsdCaps | dds::kDdsdHeight | dds::kDdsdWidth | dds::kDdsdPixelFormat | dds::kDdsdPitch;
  if (volume) flags |= dds::kDdsdDepth;
  if (has_mips) flags |= dds::kDdsdMipMapCount;
  uint32_t caps = dds::kCapsTexture;
  if (has_mips) caps |= dds::kCapsComplex | dds::kCapsMipMap;
  if (volume || top.layers > 1) caps |= dds::kCapsComplex;

  put_u32(&h[0], dds::kMagic);
  put_u32(&h[4], 124);  // DDS_HEADER.dwSize
  put_u32(&h[8], flags);
  put_u32(&h[12], uint32_t(top.height));
  put_u32(&h[16], uint32_t(top.width));
  put_u32(&h[20], uint32_t(top.width) * uint32_t(format.bytes));  // row pitch
  put_u32(&h[24], volume ? uint32_t(top.depth) : 0);
  put_u32(&h[28], uint32_t(mips.size()));
  put_u32(&h[76], 32);  // DDS_PIXELFORMAT.dwSize
  put_u32(&h[80], dds::kDdpfFourCC);
  put_u32(&h[84], dds::kFourCCDx10);
  put_u32(&h[108], caps);
  put_u32(&h[112], volume ? dds::kCaps2Volume : 0);
  put_u32(&h[128], uint32_t(format.format));
  put_u32(&h[132], volume ? dds::kDimensionTexture3D : dds::kDimensionTexture2D);
  put_u32(&h[136], 0);  // miscFlag: no cube map
  put_u32(&h[140], uint32_t(top.layers));
  put_u32(&h[144], dds::kAlphaModeUnknown);
  return h;
}

// ---- reading ---------------------------------------------------------------

// At most `max_bytes` from the start of a regular file (opened without
// blocking, so a FIFO swapped in after the caller's stat cannot hang it).
std::vector<uint8_t> read_bytes(const std::string& path, size_t max_bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0)
    throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw IoError(fmt::format("{}: expected a regular file", path));
  std::vector<uint8_t> bytes(std::min<uint64_t>(max_bytes, uint64_t(st.st_size)));
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(fmt::format("{}: read error: {}", path, std::strerror(errno)));
    if (n == 0) break;
    got += size_t(n);
  }
  bytes.resize(got);
  return bytes;
}

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
  int width, height, depth, layers, levels;
  uint64_t data_bytes;
};

// Bounds on what a header may announce (Direct3D 12: D3D12_REQ_TEXTURE2D_U_OR_V_DIMENSION,
// D3D12_REQ_TEXTURE3D_U_V_OR_W_DIMENSION, D3D12_REQ_TEXTURE2D_ARRAY_AXIS_DIMENSION), and on
// the decoded texels, so that a header cannot make the reader allocate more
// than a few GiB even when the file is that long.
constexpr uint32_t kMaxDdsSide = 16384;
constexpr uint32_t kMaxDdsVolumeSide = 2048;
constexpr uint32_t kMaxDdsArraySize = 2048;
constexpr uint64_t kMaxDdsDecodedBytes = uint64_t(4) << 30;

// Header sizes come from the file: saturate instead of wrapping, so a forged
// header cannot announce a small total (a saturated total never matches the
// file size, so nothing is allocated for it).
constexpr uint64_t kU64Max = std::numeric_limits<uint64_t>::max();
uint64_t mul_saturated(uint64_t a, uint64_t b) {
  return a != 0 && b > kU64Max / a ? kU64Max : a * b;
}
uint64_t add_saturated(uint64_t a, uint64_t b) {
  return b > kU64Max - a ? kU64Max : a + b;
}

Layout validate(const std::string& path, const DdsHeaderInfo& h) {
  if (h.size != 124)
    throw IoError(fmt::format("{}: expected DDS_HEADER size 124, got {}", path, h.size));
  if (h.pixel_format.size != 32)
    throw IoError(
        fmt::format("{}: expected DDS_PIXELFORMAT size 32, got {}", path, h.pixel_format.size));
  if (!h.has_dx10) {
    const bool four_cc = h.pixel_format.flags & dds::kDdpfFourCC;
    throw IoError(fmt::format(
        "{}: expected a DX10 header (pixel format FourCC \"DX10\"), got {}; only DX10 files "
        "are supported",
        path,
        four_cc ? fmt::format("FourCC \"{}\"", four_cc_string(h.pixel_format.four_cc))
                : fmt::format("a legacy pixel format (flags 0x{:x})", h.pixel_format.flags)));
  }
  if (h.file_size < dds::kHeaderBytes)
    throw IoError(
        fmt::format("{}: expected at least {} bytes (magic, DDS_HEADER and "
                    "DDS_HEADER_DXT10), got {}",
                    path, dds::kHeaderBytes, h.file_size));
  Layout l{};
  l.format = find_format(h.dxgi_format);
  if (!l.format)
    throw IoError(fmt::format("{}: expected a DXGI format among {}, got {}", path,
                              format_list(true), h.dxgi_format));
  const bool volume = h.resource_dimension == dds::kDimensionTexture3D;
  if (!volume && h.resource_dimension != dds::kDimensionTexture2D)
    throw IoError(
        fmt::format("{}: expected resourceDimension 3 (TEXTURE2D) or 4 (TEXTURE3D), "
                    "got {}",
                    path, h.resource_dimension));
  if (h.misc_flag & dds::kMiscTextureCube)
    throw IoError(fmt::format("{}: expected no cube map, got miscFlag 0x{:x}", path, h.misc_flag));
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
  if (volume && h.array_size != 1)
    throw IoError(fmt::format("{}: expected arraySize 1 for a volume, got {}", path, h.array_size));
  if (h.array_size < 1 || h.array_size > kMaxDdsArraySize)
    throw IoError(fmt::format("{}: expected arraySize from 1 to {}, got {}", path,
                              kMaxDdsArraySize, h.array_size));
  l.width = int(h.width), l.height = int(h.height), l.depth = int(depth);
  l.layers = int(h.array_size);
  // DirectXTex reads mipMapCount even without DDSD_MIPMAPCOUNT; 0 means 1.
  const int full = mip_count(l.width, l.height, l.depth);
  if (h.mip_map_count > uint32_t(full))
    throw IoError(fmt::format("{}: expected mipMapCount at most {} for {}x{}x{}, got {}", path, full,
                              l.width, l.height, l.depth, h.mip_map_count));
  l.levels = std::max(1, int(h.mip_map_count));
  uint64_t per_layer = 0;
  for (int i = 0; i < l.levels; ++i) {
    const uint64_t texels =
        mul_saturated(mul_saturated(std::max(1, l.width >> i), std::max(1, l.height >> i)),
                      std::max(1, l.depth >> i));
    per_layer = add_saturated(per_layer, mul_saturated(texels, uint64_t(l.format->bytes)));
  }
  l.data_bytes = mul_saturated(per_layer, uint64_t(l.layers));
  const uint64_t decoded = mul_saturated(
      mul_saturated(l.data_bytes / uint64_t(l.format->bytes), uint64_t(l.format->components)),
      sizeof(float));
  if (decoded > kMaxDdsDecodedBytes)
    throw IoError(fmt::format(
        "{}: expected at most {} GiB of float32 texels (all mip levels and layers), got {} "
        "bytes for {}x{}x{} with arraySize {} and {} mip levels",
        path, kMaxDdsDecodedBytes >> 30, decoded, l.width, l.height, l.depth, l.layers, l.levels));
  const uint64_t got = h.file_size - dds::kHeaderBytes;
  if (got != l.data_bytes)
    throw IoError(
        fmt::format("{}: expected {} bytes of pixel data after the {}-byte header, got "
                    "{}{}",
                    path, l.data_bytes, dds::kHeaderBytes, got,
                    got < l.data_bytes ? " (truncated file)" : " (trailing bytes)"));
  return l;
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
    for (const FormatInfo& f : kFormats) v.push_back(f.format);
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

DdsFormat dds_format_from_name(const std::string& name, const std::string& context) {
  const std::string prefix = "DXGI_FORMAT_";
  const std::string bare =
      name.compare(0, prefix.size(), prefix) == 0 ? name.substr(prefix.size()) : name;
  for (const FormatInfo& f : kFormats)
    if (bare == f.name) return f.format;
  std::vector<std::string> names;
  for (const FormatInfo& f : kFormats) names.push_back(f.name);
  const std::string* best = closest_name(bare, names, 2);
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

void write_dds(const std::string& path, const std::vector<Texture>& mips, DdsFormat format) {
  const FormatInfo& f = info(format);
  check_writable(path, mips, f);
  const std::vector<uint8_t> header = make_header(mips, f);

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    throw IoError(fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno)));
  out.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
  // Array slices outermost, then mip levels; a level's depth slices are
  // contiguous in both Texture and DDS order, so one loop serves 2D arrays
  // (slice -> mips) and volumes (mip -> slices, with a single "slice").
  const int nc = mips[0].channel_count();
  std::vector<uint8_t> buf;
  for (int layer = 0; layer < mips[0].layers && out; ++layer) {
    for (const Texture& m : mips) {
      const size_t texels = size_t(m.width) * m.height * m.depth;
      buf.resize(texels * size_t(f.bytes));
      const float* src = m.texel(0, 0, 0, layer);
      for (size_t t = 0; t < texels; ++t) encode_texel(format, src + t * nc, nc, &buf[t * f.bytes]);
      out.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(buf.size()));
    }
  }
  out.close();
  if (!out) {
    const std::string reason = std::strerror(errno);
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: write failed: {}", path, reason));
  }
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

DdsImage read_dds(const std::string& path) {
  const DdsHeaderInfo h = read_dds_header(path);
  const Layout l = validate(path, h);  // also bounds the allocation by the file size
  const std::vector<uint8_t> bytes = read_bytes(path, size_t(h.file_size));
  if (bytes.size() != h.file_size)
    throw IoError(fmt::format("{}: expected {} bytes, got {} (file changed while reading)", path,
                              h.file_size, bytes.size()));
  DdsImage image;
  image.format = l.format->format;
  const int nc = l.format->components;
  for (int i = 0; i < l.levels; ++i) {
    const Shape s = level_shape({l.width, l.height, l.depth}, i);
    image.mips.emplace_back(s.width, s.height, s.depth, l.layers, channel_names(nc));
  }
  const uint8_t* p = bytes.data() + dds::kHeaderBytes;
  for (int layer = 0; layer < l.layers; ++layer) {
    for (Texture& m : image.mips) {
      const size_t texels = size_t(m.width) * m.height * m.depth;
      float* dst = m.texel(0, 0, 0, layer);
      for (size_t t = 0; t < texels; ++t, p += l.format->bytes)
        decode_texel(image.format, p, dst + t * nc);
    }
  }
  return image;
}

}  // namespace skybake

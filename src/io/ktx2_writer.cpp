// KTX2 writer (ktx2.hpp for the layout, the key/value data and the conversions).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "core/half.hpp"
#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "io/ktx2.hpp"
#include "io/le_bytes.hpp"
#include "io/size_math.hpp"

namespace skybake {

namespace {

using sizes::align_up;

// Encodes one texel of `nc` channels (nc <= components of the format).
void encode_texel(const Ktx2FormatInfo& f, const float* src, int nc, uint8_t* dst) {
  float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // missing components 0, missing alpha 1
  std::copy(src, src + nc, v);
  for (int c = 0; c < f.components; ++c) {
    switch (f.encoding) {
      case Ktx2Encoding::float32:
        le::put_f32(dst + 4 * c, v[c]);
        break;
      case Ktx2Encoding::half:
        le::put_u16(dst + 2 * c, half_from_float(std::clamp(v[c], -kHalfMax, kHalfMax)));
        break;
      case Ktx2Encoding::unorm8:
        dst[c] = uint8_t(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f));
        break;
      case Ktx2Encoding::bc:  // whole slices at a time: level_bytes
        break;
    }
  }
}

struct Shape {
  int width, height, depth;
};

Shape level_shape(const Texture& top, int level) {
  return {std::max(1, top.width >> level), std::max(1, top.height >> level),
          std::max(1, top.depth >> level)};
}

void check_metadata(const std::string& path, const Metadata& meta) {
  for (const auto& [key, value] : meta) {
    if (key == "channels")
      throw Error(fmt::format("{}: expected a metadata key other than the reserved '{}channels'",
                              path, ktx2::kMetaPrefix));
    if (key.empty() || key.find('\0') != std::string::npos)
      throw IoError(
          fmt::format("{}: expected metadata keys without NUL bytes, got \"{}\"", path, key));
  }
}

// Refuses anything that would not make a valid file, before any I/O.
void check_writable(const std::string& path, const MipLevels& mips, const Ktx2FormatInfo& f,
                    FiniteCheck level0) {
  if (mips.empty()) throw IoError(path + ": expected at least one mip level, got none");
  const Texture& top = *mips[0];
  if (top.width < 1 || top.height < 1 || top.depth < 1 || top.layers < 1)
    throw IoError(fmt::format("{}: expected a non-empty texture, got {}x{}x{} with {} layers", path,
                              top.width, top.height, top.depth, top.layers));
  if (top.depth > 1 && top.layers > 1)
    throw IoError(
        fmt::format("{}: expected a 3D texture or a 2D array (skybake writes no 3D arrays), got {}",
                    path, top.shape_string()));
  if (top.channel_count() < 1 || top.channel_count() > f.components)
    throw IoError(fmt::format("{}: expected 1 to {} channels for {}, got {}", path, f.components,
                              f.name, top.channel_count()));
  const int full = mip_count(top.width, top.height, top.depth);
  if (int(mips.size()) > full)
    throw IoError(fmt::format("{}: expected at most {} mip levels for {}, got {}", path, full,
                              top.shape_string(), mips.size()));
  for (size_t i = 0; i < mips.size(); ++i) {
    const Texture& m = *mips[i];
    const Shape s = level_shape(top, int(i));
    if (m.width != s.width || m.height != s.height || m.depth != s.depth || m.layers != top.layers)
      throw IoError(fmt::format(
          "{}: mip {}: expected shape {}x{}x{} with {} layers, got {}x{}x{} with {} layers", path,
          i, s.width, s.height, s.depth, top.layers, m.width, m.height, m.depth, m.layers));
    if (m.channels != top.channels)
      throw IoError(fmt::format("{}: mip {}: expected channels [{}], got [{}]", path, i,
                                fmt::join(top.channels, ","), fmt::join(m.channels, ",")));
    if (m.data.size() != m.texel_count() * m.channels.size())
      throw IoError(fmt::format("{}: mip {}: expected {} values, got {}", path, i,
                                m.texel_count() * m.channels.size(), m.data.size()));
    if (i > 0 || level0 == FiniteCheck::run)
      check_finite(m, i == 0 ? path : fmt::format("{}: mip {}", path, i));
  }
  check_metadata(path, top.metadata);
}

// A NUL-terminated UTF-8 value.
std::string text_value(const std::string& s) {
  return s + '\0';
}

// The key/value data: entries sorted by key (std::map orders bytes as
// unsigned, which is Unicode code point order for UTF-8), each padded to 4.
std::vector<uint8_t> key_value_data(const Texture& top) {
  std::map<std::string, std::string> kv;
  kv["KTXorientation"] = text_value(top.depth > 1 ? "rdi" : "rd");
  kv["KTXwriter"] = text_value("skybake " SKYBAKE_VERSION);
  kv[std::string(ktx2::kMetaPrefix) + "channels"] = text_value(nlohmann::json(top.channels).dump());
  for (const auto& [key, value] : top.metadata)
    kv[ktx2::kMetaPrefix + key] = text_value(meta_to_json(value).dump());
  std::vector<uint8_t> out;
  for (const auto& [key, value] : kv) {
    const uint32_t length = uint32_t(key.size() + 1 + value.size());
    const size_t at = out.size();
    out.resize(align_up(at + 4 + length, 4), 0);
    le::put_u32(&out[at], length);
    std::memcpy(&out[at + 4], key.data(), key.size());  // the NUL after it is already 0
    std::memcpy(&out[at + 4 + key.size() + 1], value.data(), value.size());
  }
  return out;
}

// Header, index, level index, descriptor, key/value data and the padding
// before the first (smallest) level: everything before the level data.
// `faces`: 1, or 6 for cube maps (layers six faces per cube).
std::vector<uint8_t> file_head(const MipLevels& mips, const Ktx2FormatInfo& f, uint32_t faces) {
  const Texture& top = *mips[0];
  const uint32_t levels = uint32_t(mips.size());
  const uint32_t layers = uint32_t(top.layers) / faces;
  const std::vector<uint8_t> dfd = encode_dfd(dfd_for_vk_format(uint32_t(f.format)));
  const std::vector<uint8_t> kvd = key_value_data(top);
  const uint32_t dfd_offset = ktx2::kHeaderBytes + ktx2::kLevelIndexEntryBytes * levels;
  const uint32_t kvd_offset = dfd_offset + uint32_t(dfd.size());
  const uint64_t align = ktx2_level_alignment(f);
  const uint64_t data_start = align_up(kvd_offset + kvd.size(), align);

  std::vector<uint8_t> h(data_start, 0);
  std::memcpy(h.data(), ktx2::kIdentifier, 12);
  const uint32_t fields[] = {uint32_t(f.format),
                             f.type_size,
                             uint32_t(top.width),
                             uint32_t(top.height),
                             top.depth > 1 ? uint32_t(top.depth) : 0,
                             layers > 1 ? layers : 0,
                             faces,
                             levels,
                             0,  // supercompressionScheme: none
                             dfd_offset,
                             uint32_t(dfd.size()),
                             kvd_offset,
                             uint32_t(kvd.size())};
  for (size_t i = 0; i < std::size(fields); ++i) le::put_u32(&h[12 + 4 * i], fields[i]);
  // sgdByteOffset and sgdByteLength (bytes 64..79) stay 0.
  // Levels are stored smallest first; the index lists level 0 first.
  uint64_t offset = data_start;
  for (uint32_t p = levels; p-- > 0;) {
    const Texture& m = *mips[p];
    const uint64_t bytes = ktx2_level_bytes(f, uint64_t(m.width), uint64_t(m.height),
                                            uint64_t(m.depth), uint64_t(m.layers));
    uint8_t* entry = &h[ktx2::kHeaderBytes + ktx2::kLevelIndexEntryBytes * p];
    le::put_u64(entry, offset);
    le::put_u64(entry + 8, bytes);
    le::put_u64(entry + 16, bytes);  // uncompressedByteLength: no supercompression
    offset = align_up(offset + bytes, align);
  }
  std::memcpy(&h[dfd_offset], dfd.data(), dfd.size());
  std::memcpy(&h[kvd_offset], kvd.data(), kvd.size());
  return h;
}

// One level's bytes in file order (layers, slices, rows), padded with
// zeros to `padded` bytes.
std::vector<uint8_t> level_bytes(const Texture& m, const Ktx2FormatInfo& f, size_t padded,
                                 BcSliceCache* cache) {
  const int nc = m.channel_count();
  std::vector<uint8_t> out;
  out.reserve(padded);
  if (f.encoding == Ktx2Encoding::bc) {
    // Block compression works on 2D slices; a 3D level is its slices in
    // order (block depth 1).
    std::vector<uint8_t> scratch;
    for (int layer = 0; layer < m.layers; ++layer)
      for (int z = 0; z < m.depth; ++z) {
        const std::vector<uint8_t>& blocks =
            encode_bc_slice(cache, scratch, m.texel(0, 0, z, layer), m.width, m.height, nc, f.bc);
        out.insert(out.end(), blocks.begin(), blocks.end());
      }
  } else {
    out.resize(m.texel_count() * size_t(f.block_bytes));
    for (size_t t = 0; t < m.texel_count(); ++t)
      encode_texel(f, m.data.data() + t * size_t(nc), nc, &out[t * size_t(f.block_bytes)]);
  }
  out.resize(padded, 0);
  return out;
}

// The head, then the levels smallest first (write_ktx2, write_ktx2_cube).
void write_ktx2_file(const std::string& path, const MipLevels& mips, const Ktx2FormatInfo& f,
                     const std::vector<uint8_t>& head, BcSliceCache* cache) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    throw IoError(fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno)));
  out.write(reinterpret_cast<const char*>(head.data()), std::streamsize(head.size()));
  const uint64_t align = ktx2_level_alignment(f);
  try {
    for (size_t p = mips.size(); p-- > 0 && out;) {  // smallest level first
      const Texture& m = *mips[p];
      const uint64_t bytes = ktx2_level_bytes(f, uint64_t(m.width), uint64_t(m.height),
                                              uint64_t(m.depth), uint64_t(m.layers));
      // Padded to the next level's alignment; the largest level ends the file.
      const std::vector<uint8_t> buf =
          level_bytes(m, f, size_t(p == 0 ? bytes : align_up(bytes, align)), cache);
      out.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(buf.size()));
    }
  } catch (...) {  // the block encoder's plugin missing: no partial file
    out.close();
    std::remove(path.c_str());
    throw;
  }
  out.close();
  if (!out) {
    const std::string reason = std::strerror(errno);
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: write failed: {}", path, reason));
  }
}

}  // namespace

void write_ktx2(const std::string& path, const std::vector<Texture>& mips, Ktx2Format format,
                FiniteCheck level0) {
  MipLevels levels;
  for (const Texture& m : mips) levels.push_back(&m);
  write_ktx2(path, levels, format, level0);
}

void write_ktx2(const std::string& path, const MipLevels& mips, Ktx2Format format,
                FiniteCheck level0, BcSliceCache* cache) {
  const Ktx2FormatInfo& f = ktx2_format_info(format);
  check_writable(path, mips, f, level0);
  write_ktx2_file(path, mips, f, file_head(mips, f, 1), cache);
}

void write_ktx2_cube(const std::string& path, const MipLevels& mips, Ktx2Format format,
                     FiniteCheck level0) {
  const Ktx2FormatInfo& f = ktx2_format_info(format);
  check_writable(path, mips, f, level0);
  const Texture& top = *mips[0];
  if (top.depth != 1 || top.width != top.height || top.layers % 6 != 0)
    throw IoError(fmt::format("{}: expected square 2D faces, six per cube, got {}", path,
                              top.shape_string()));
  write_ktx2_file(path, mips, f, file_head(mips, f, 6), nullptr);
}

}  // namespace skybake

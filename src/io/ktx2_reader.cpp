// Strict KTX2 reader (ktx2.hpp for what it accepts). Every size in the file
// is bounded and checked against the file's length before it is used, so a
// forged header can neither make the reader allocate more than a few GiB nor
// read past what it holds (fuzz/ktx2_reader_fuzz.cpp).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/half.hpp"
#include "core/json_input.hpp"
#include "core/metadata_json.hpp"
#include "core/mip_chain.hpp"
#include "io/file_bytes.hpp"
#include "io/block_compression.hpp"
#include "io/ktx2.hpp"
#include "io/le_bytes.hpp"
#include "io/size_math.hpp"

namespace skybake {

namespace {

// Bounds on what a header may announce (the Vulkan limits most devices give:
// maxImageDimension2D 16384, maxImageDimension3D 2048, maxImageArrayLayers
// 2048), and on the decoded texels, as for DDS.
constexpr uint32_t kMaxSide = 16384;
constexpr uint32_t kMaxVolumeSide = 2048;
constexpr uint32_t kMaxLayers = 2048;
constexpr uint64_t kMaxDecodedBytes = uint64_t(4) << 30;

using sizes::align_up;

uint64_t file_size_of(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw IoError(fmt::format("{}: expected a regular file", path));
  return uint64_t(st.st_size);
}

Ktx2Header parse_header(const std::string& path, const std::vector<uint8_t>& b,
                        uint64_t file_size) {
  if (b.size() < ktx2::kHeaderBytes)
    throw IoError(fmt::format(
        "{}: expected at least {} bytes (identifier, header and index), got {} (truncated file)",
        path, ktx2::kHeaderBytes, b.size()));
  if (std::memcmp(b.data(), ktx2::kIdentifier, 12) != 0)
    throw IoError(fmt::format("{}: expected the KTX2 identifier «KTX 20»\\r\\n\\x1A\\n, got {:02x}",
                              path, fmt::join(b.begin(), b.begin() + 12, " ")));
  Ktx2Header h;
  h.file_size = file_size;
  uint32_t* fields[] = {&h.vk_format,       &h.type_size,       &h.pixel_width,
                        &h.pixel_height,    &h.pixel_depth,     &h.layer_count,
                        &h.face_count,      &h.level_count,     &h.supercompression_scheme,
                        &h.dfd_byte_offset, &h.dfd_byte_length, &h.kvd_byte_offset,
                        &h.kvd_byte_length};
  for (size_t i = 0; i < std::size(fields); ++i) *fields[i] = le::get_u32(&b[12 + 4 * i]);
  h.sgd_byte_offset = le::get_u64(&b[64]);
  h.sgd_byte_length = le::get_u64(&b[72]);
  return h;
}

// The header's fields against each other and the bounds; the format.
const Ktx2FormatInfo& validate_header(const std::string& path, const Ktx2Header& h) {
  const Ktx2FormatInfo* f = find_ktx2_format(h.vk_format);
  if (!f)
    throw IoError(fmt::format("{}: expected a vkFormat among {}, got {}", path,
                              ktx2_format_list(true), h.vk_format));
  if (h.type_size != f->type_size)
    throw IoError(fmt::format("{}: expected typeSize {} for {}, got {}", path, f->type_size,
                              f->name, h.type_size));
  if (h.face_count != 1 && h.face_count != 6)
    throw IoError(fmt::format("{}: expected faceCount 1 or 6 (a cube map), got {}", path,
                              h.face_count));
  if (h.face_count == 6 && (h.pixel_width != h.pixel_height || h.pixel_depth != 0))
    throw IoError(fmt::format("{}: expected square 2D faces for a cube map, got {}x{}x{}", path,
                              h.pixel_width, h.pixel_height, h.pixel_depth));
  if (h.supercompression_scheme != 0)
    throw IoError(fmt::format("{}: expected supercompressionScheme 0 (none), got {}", path,
                              h.supercompression_scheme));
  if (h.pixel_height == 0)
    throw IoError(
        fmt::format("{}: expected pixelHeight of at least 1, got 0 (a 1D texture)", path));
  if (h.pixel_depth > 0 && h.layer_count > 0)
    throw IoError(
        fmt::format("{}: expected a 3D texture or a 2D array, got a 3D array "
                    "(pixelDepth {}, layerCount {})",
                    path, h.pixel_depth, h.layer_count));
  const bool volume = h.pixel_depth > 0;
  const uint32_t limit = volume ? kMaxVolumeSide : kMaxSide;
  const std::pair<const char*, uint32_t> sides[] = {{"pixelWidth", h.pixel_width},
                                                    {"pixelHeight", h.pixel_height},
                                                    {"pixelDepth", h.pixel_depth}};
  for (const auto& [name, value] : sides)  // pixelDepth 0 (a 2D texture) is within the range
    if ((value < 1 && name != sides[2].first) || value > limit)
      throw IoError(fmt::format("{}: expected {} from 1 to {} for {}, got {}", path, name, limit,
                                volume ? "a 3D texture" : "a 2D texture", value));
  if (h.layer_count > kMaxLayers)
    throw IoError(fmt::format("{}: expected layerCount from 0 to {}, got {}", path, kMaxLayers,
                              h.layer_count));
  const int full =
      mip_count(int(h.pixel_width), int(h.pixel_height), int(std::max<uint32_t>(1, h.pixel_depth)));
  if (h.level_count == 0)
    throw IoError(
        fmt::format("{}: expected levelCount from 1 to {}, got 0 (\"generate mips\"; "
                    "skybake writes every level it means)",
                    path, full));
  if (h.level_count > uint32_t(full))
    throw IoError(fmt::format("{}: expected levelCount from 1 to {} for {}x{}x{}, got {}", path,
                              full, h.pixel_width, h.pixel_height, h.pixel_depth, h.level_count));
  return *f;
}

struct Layout {
  int width, height, depth, layers, levels;
  uint64_t kvd_end;                  // where the key/value data (or the descriptor) ends
  std::vector<Ktx2LevelIndex> want;  // the level index a writer must produce
  uint64_t file_bytes;               // and the file's length
  uint64_t decoded_bytes;            // float32 texels of every level and layer
};

// The one layout a writer may produce for this header, index and descriptor size.
Layout expected_layout(const std::string& path, const Ktx2Header& h, const Ktx2FormatInfo& f) {
  Layout l{};
  l.width = int(h.pixel_width), l.height = int(h.pixel_height);
  l.depth = int(std::max<uint32_t>(1, h.pixel_depth));
  // A cube's faces follow each other within a layer (KTX 2.0 "Level Images").
  l.layers = int(std::max<uint32_t>(1, h.layer_count) * h.face_count);
  l.levels = int(h.level_count);
  const uint64_t level_index_end =
      ktx2::kHeaderBytes + uint64_t(ktx2::kLevelIndexEntryBytes) * h.level_count;
  if (h.dfd_byte_offset != level_index_end)
    throw IoError(fmt::format("{}: expected dfdByteOffset {} (right after the level index), got {}",
                              path, level_index_end, h.dfd_byte_offset));
  const uint64_t dfd_end = uint64_t(h.dfd_byte_offset) + h.dfd_byte_length;
  if (h.kvd_byte_length == 0 && h.kvd_byte_offset != 0)
    throw IoError(fmt::format("{}: expected kvdByteOffset 0 with no key/value data, got {}", path,
                              h.kvd_byte_offset));
  if (h.kvd_byte_length > 0 && h.kvd_byte_offset != dfd_end)
    throw IoError(fmt::format("{}: expected kvdByteOffset {} (right after the descriptor), got {}",
                              path, dfd_end, h.kvd_byte_offset));
  if (h.sgd_byte_offset != 0 || h.sgd_byte_length != 0)
    throw IoError(
        fmt::format("{}: expected no supercompression global data (sgdByteOffset and "
                    "sgdByteLength 0), got {} and {}",
                    path, h.sgd_byte_offset, h.sgd_byte_length));
  l.kvd_end = dfd_end + h.kvd_byte_length;
  uint64_t decoded = 0;
  l.want.resize(size_t(l.levels));
  const uint64_t align = ktx2_level_alignment(f);
  uint64_t offset = align_up(l.kvd_end, align);
  for (int p = l.levels; p-- > 0;) {
    const uint64_t w = uint64_t(std::max(1, l.width >> p)),
                   hh = uint64_t(std::max(1, l.height >> p));
    const uint64_t d = uint64_t(std::max(1, l.depth >> p));
    const uint64_t bytes = ktx2_level_bytes(f, w, hh, d, uint64_t(l.layers));
    decoded += w * hh * d * uint64_t(l.layers) * uint64_t(f.components) * sizeof(float);
    l.want[size_t(p)] = {offset, bytes, bytes};
    offset = p == 0 ? offset + bytes : align_up(offset + bytes, align);
  }
  if (decoded > kMaxDecodedBytes)
    throw IoError(fmt::format(
        "{}: expected at most {} GiB of float32 texels (all levels and "
        "layers), got {} bytes for {}x{}x{} with {} layers and {} levels",
        path, kMaxDecodedBytes >> 30, decoded, l.width, l.height, l.depth, l.layers, l.levels));
  l.file_bytes = offset;
  l.decoded_bytes = decoded;
  return l;
}

void check_level_index(const std::string& path, const Ktx2Header& h, const Layout& l) {
  for (size_t p = 0; p < l.want.size(); ++p) {
    const Ktx2LevelIndex& got = h.levels[p];
    const Ktx2LevelIndex& want = l.want[p];
    if (got.byte_offset != want.byte_offset || got.byte_length != want.byte_length ||
        got.uncompressed_byte_length != want.uncompressed_byte_length)
      throw IoError(fmt::format(
          "{}: level {}: expected byteOffset {}, byteLength {}, uncompressedByteLength {} "
          "(levels smallest first, each aligned), got {}, {}, {}",
          path, p, want.byte_offset, want.byte_length, want.uncompressed_byte_length,
          got.byte_offset, got.byte_length, got.uncompressed_byte_length));
  }
}

void check_zero(const std::string& path, const std::vector<uint8_t>& b, uint64_t from, uint64_t to,
                const char* what) {
  for (uint64_t i = from; i < to; ++i)
    if (b[size_t(i)] != 0)
      throw IoError(fmt::format("{}: expected zero {} at bytes {} to {}, got 0x{:02x} at {}", path,
                                what, from, to, b[size_t(i)], i));
}

// A key as messages quote it: a forged key may be as long as the key/value data.
std::string key_text(const std::string& key) {
  return key.size() > 64 ? key.substr(0, 64) + "..." : key;
}

// Key/value pairs in file order (KTX2 "Key/Value Data"): lengths, sorting,
// uniqueness and zero padding checked.
std::vector<std::pair<std::string, std::string>> parse_key_values(const std::string& path,
                                                                  const std::vector<uint8_t>& b,
                                                                  uint64_t start, uint64_t length) {
  std::vector<std::pair<std::string, std::string>> kv;
  uint64_t at = start;
  const uint64_t end = start + length;
  while (at < end) {
    if (end - at < 4)
      throw IoError(
          fmt::format("{}: key/value data: expected a keyAndValueByteLength at byte {}, "
                      "{} bytes remain",
                      path, at, end - at));
    const uint32_t n = le::get_u32(&b[size_t(at)]);
    if (n < 2 || n > end - at - 4)
      throw IoError(
          fmt::format("{}: key/value data: expected keyAndValueByteLength from 2 to {} "
                      "at byte {}, got {}",
                      path, end - at - 4, at, n));
    const char* p = reinterpret_cast<const char*>(&b[size_t(at + 4)]);
    const void* nul = std::memchr(p, 0, n);
    if (!nul || nul == p)
      throw IoError(
          fmt::format("{}: key/value data: expected a non-empty NUL-terminated key at "
                      "byte {}",
                      path, at + 4));
    const size_t key_len = size_t(static_cast<const char*>(nul) - p);
    std::string key(p, key_len), value(p + key_len + 1, n - key_len - 1);
    if (!kv.empty() && !(kv.back().first < key))
      throw IoError(
          fmt::format("{}: key/value data: expected keys sorted and unique, got \"{}\" "
                      "after \"{}\"",
                      path, key_text(key), key_text(kv.back().first)));
    const uint64_t next = align_up(at + 4 + n, 4);
    if (next > end)
      throw IoError(fmt::format("{}: key/value data: the padding of \"{}\" runs past kvdByteLength",
                                path, key_text(key)));
    check_zero(path, b, at + 4 + n, next, "valuePadding");
    kv.emplace_back(std::move(key), std::move(value));
    at = next;
  }
  return kv;
}

// A NUL-terminated UTF-8 value without its NUL; IoError when it has none.
std::string text_of(const std::string& path, const std::string& key, const std::string& value) {
  if (value.empty() || value.back() != '\0' || value.find('\0') != value.size() - 1)
    throw IoError(
        fmt::format("{}: expected {} to hold one NUL-terminated string", path, key_text(key)));
  return value.substr(0, value.size() - 1);
}

nlohmann::json json_of(const std::string& path, const std::string& key, const std::string& value) {
  const std::string text = text_of(path, key, value);
  ParsedJson parsed = parse_json_text(text);
  if (!parsed.value && parsed.why != "invalid JSON")
    throw IoError(
        fmt::format("{}: expected {} to hold JSON: it {}", path, key_text(key), parsed.why));
  if (!parsed.value)
    throw IoError(
        fmt::format("{}: expected {} to hold JSON, got '{}'", path, key_text(key),
                    text.substr(0, 64)));
  return std::move(*parsed.value);
}

std::vector<std::string> channels_of(const std::string& path, const nlohmann::json& j,
                                     int components) {
  std::vector<std::string> names;
  std::set<std::string> seen;
  const bool ok = j.is_array() && !j.empty() && int(j.size()) <= components &&
                  std::all_of(j.begin(), j.end(), [&](const nlohmann::json& n) {
                    if (!n.is_string() || n.get<std::string>().empty()) return false;
                    names.push_back(n.get<std::string>());
                    return seen.insert(names.back()).second;
                  });
  if (!ok)
    throw IoError(
        fmt::format("{}: expected skybake.channels to be an array of 1 to {} distinct "
                    "non-empty names, got {}",
                    path, components, json_excerpt(j, 120)));
  return names;
}

// Channels and metadata from the key/value data; checks KTXorientation.
void apply_key_values(const std::string& path, const Ktx2Image& image, int components,
                      std::vector<std::string>& channels, Metadata& meta) {
  static const char* kRgba[] = {"R", "G", "B", "A"};
  channels.assign(kRgba, kRgba + components);
  const std::string prefix = ktx2::kMetaPrefix;
  const bool volume = image.header.pixel_depth > 0;
  for (const auto& [key, value] : image.key_values) {
    if (key == "KTXorientation") {
      const std::string o = text_of(path, key, value), want = volume ? "rdi" : "rd";
      if (o != want)
        throw IoError(
            fmt::format("{}: expected KTXorientation \"{}\" (first texel top-left{}), "
                        "got \"{}\"",
                        path, want, volume ? ", front" : "", o.substr(0, 16)));
    } else if (key == prefix + "channels") {
      channels = channels_of(path, json_of(path, key, value), components);
    } else if (key.compare(0, prefix.size(), prefix) == 0) {
      const nlohmann::json j = json_of(path, key, value);
      std::string why;
      std::optional<MetaValue> v = meta_from_json(j, &why);
      if (!v) throw IoError(fmt::format("{}: key/value '{}': {}", path, key_text(key), why));
      meta[key.substr(prefix.size())] = *v;
    }
  }
}

void decode_texel(const Ktx2FormatInfo& f, const uint8_t* src, float* dst) {
  for (int c = 0; c < f.components; ++c) {
    switch (f.encoding) {
      case Ktx2Encoding::float32:
        dst[c] = le::get_f32(src + 4 * c);
        break;
      case Ktx2Encoding::half:
        dst[c] = float_from_half(le::get_u16(src + 2 * c));
        break;
      case Ktx2Encoding::unorm8:
        dst[c] = src[c] / 255.0f;
        break;
      case Ktx2Encoding::bc:  // whole slices at a time: decode_level
        break;
    }
  }
}

// Decodes one level at `src` into `m`, keeping its channels' components.
void decode_level(const uint8_t* src, const Ktx2FormatInfo& f, Texture& m) {
  const size_t nc = m.channels.size();
  if (f.encoding == Ktx2Encoding::bc) {
    // Slice by slice (block depth 1), as the writer encodes them.
    const size_t decoded = size_t(bc_decoded_channel_count(f.bc));
    for (int layer = 0; layer < m.layers; ++layer)
      for (int z = 0; z < m.depth; ++z) {
        const std::vector<float> texels = decode_bc(src, m.width, m.height, f.bc);
        float* dst = m.texel(0, 0, z, layer);
        for (size_t t = 0; t < size_t(m.width) * size_t(m.height); ++t)
          std::copy(&texels[t * decoded], &texels[t * decoded] + nc, dst + t * nc);
        src += bc_slice_bytes(m.width, m.height, f.bc);
      }
    return;
  }
  float texel[4];
  for (size_t t = 0; t < m.texel_count(); ++t, src += f.block_bytes) {
    decode_texel(f, src, texel);
    std::copy(texel, texel + nc, &m.data[t * nc]);
  }
}

void decode_levels(const std::vector<uint8_t>& b, const Layout& l, const Ktx2FormatInfo& f,
                   Ktx2Image& image, const std::vector<std::string>& channels) {
  for (int p = 0; p < l.levels; ++p) {
    Texture m(std::max(1, l.width >> p), std::max(1, l.height >> p), std::max(1, l.depth >> p),
              l.layers, channels);
    decode_level(b.data() + l.want[size_t(p)].byte_offset, f, m);
    image.mips.push_back(std::move(m));
  }
}

}  // namespace

Ktx2Image read_ktx2(const std::string& path, uint64_t budget) {
  const uint64_t size = file_size_of(path);
  Ktx2Image image;
  Ktx2Header& h = image.header;
  h = parse_header(path, read_bytes(path, ktx2::kHeaderBytes), size);
  const Ktx2FormatInfo& f = validate_header(path, h);
  image.format = f.format;
  image.cube = h.face_count == 6;
  const Layout l = expected_layout(path, h, f);  // bounds every size by the header's shape
  if (size != l.file_bytes)
    throw IoError(fmt::format(
        "{}: expected {} bytes (header, level index, descriptor, key/value data and {} levels), "
        "got {}{}",
        path, l.file_bytes, l.levels, size,
        size < l.file_bytes ? " (truncated file)" : " (trailing bytes)"));
  // The whole file is read, then decoded into textures of every level.
  check_read_budget(path, l.decoded_bytes + size, budget,
                    fmt::format("{}x{}x{} with {} layers and {} levels as float32 with {} "
                                "channels, and the file's bytes",
                                l.width, l.height, l.depth, l.layers, l.levels, f.components));
  const std::vector<uint8_t> b = read_bytes(path, size);
  if (b.size() != size)
    throw IoError(fmt::format("{}: expected {} bytes, got {} (file changed while reading)", path,
                              size, b.size()));
  for (uint32_t p = 0; p < h.level_count; ++p) {
    const uint8_t* e = &b[ktx2::kHeaderBytes + ktx2::kLevelIndexEntryBytes * p];
    h.levels.push_back({le::get_u64(e), le::get_u64(e + 8), le::get_u64(e + 16)});
  }
  check_level_index(path, h, l);
  image.dfd = parse_dfd(path, &b[h.dfd_byte_offset], h.dfd_byte_length);
  if (const std::string why = dfd_mismatch(image.dfd, h.vk_format); !why.empty())
    throw IoError(
        fmt::format("{}: data format descriptor does not describe {}: {}", path, f.name, why));
  image.key_values = parse_key_values(path, b, h.kvd_byte_offset, h.kvd_byte_length);
  check_zero(path, b, l.kvd_end, l.want.back().byte_offset, "mipPadding");
  for (int p = l.levels - 1; p > 0; --p)
    check_zero(path, b, l.want[size_t(p)].byte_offset + l.want[size_t(p)].byte_length,
               l.want[size_t(p) - 1].byte_offset, "mipPadding");
  std::vector<std::string> channels;
  Metadata meta;
  apply_key_values(path, image, f.components, channels, meta);
  decode_levels(b, l, f, image, channels);
  image.mips.front().metadata = std::move(meta);
  return image;
}

}  // namespace skybake

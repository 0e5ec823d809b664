// The structure walked here is OpenVDB's io::Archive / io::File layout:
// header, file metadata, then per grid a descriptor (name, type, instance
// parent, grid/block/end offsets), the grid's compression flags, metadata,
// transform, topology (root tiles and children, internal nodes' masks and
// compressed values, leaves' value masks) and, from the block offset, the
// leaves' buffers in root-table order.
#include "io/vdb_layout.hpp"

#include <algorithm>
#include <array>
#include <bitset>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include <fmt/format.h>
#include <openvdb/Metadata.h>

#include "core/error.hpp"

namespace skybake {

namespace {

constexpr int64_t kMagic = 0x56444220;               // "VDB "
constexpr uint32_t kOldestVersion = 222;             // node mask compression
constexpr uint32_t kNewestVersion = 224;             // multipass I/O, OpenVDB 10's
constexpr uint32_t kZip = 0x1, kActiveMask = 0x2, kBlosc = 0x4;
constexpr int32_t kCoordLimit = 1 << 30;             // keeps OpenVDB's bbox sums in int32
constexpr uint64_t kBloscHeaderBytes = 16;

using Coord = std::array<int32_t, 3>;

class Walker {
 public:
  explicit Walker(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw IoError(fmt::format("{}: cannot open for reading", path));
    in_.seekg(0, std::ios::end);
    size_ = uint64_t(in_.tellg());
    in_.seekg(0);
  }

  [[noreturn]] void fail(const std::string& rule) const {
    throw IoError(
        fmt::format("{}: not a VDB skybake can read safely: {} (at byte {})", path_, rule, pos_));
  }
  uint64_t pos() const { return pos_; }
  uint64_t size() const { return size_; }
  uint64_t left() const { return size_ - pos_; }

  void need(uint64_t n, const char* what) const {
    if (n > left()) fail(fmt::format("{} needs {} bytes, {} remain", what, n, left()));
  }
  void read(void* dst, uint64_t n, const char* what) {
    need(n, what);
    in_.read(static_cast<char*>(dst), std::streamsize(n));
    if (!in_) fail(fmt::format("cannot read {}", what));
    pos_ += n;
  }
  template <typename T>
  T get(const char* what) {
    T v;
    read(&v, sizeof v, what);
    return v;
  }
  void skip(uint64_t n, const char* what) {
    need(n, what);
    seek(pos_ + n, what);
  }
  void seek(uint64_t to, const char* what) {
    if (to > size_) fail(fmt::format("{} at byte {} is past the end ({} bytes)", what, to, size_));
    pos_ = to;
    in_.seekg(std::streamoff(to));
  }
  std::string string(const char* what) {
    const uint32_t n = get<uint32_t>(what);
    need(n, what);
    std::string s(n, '\0');
    read(s.data(), n, what);
    return s;
  }

 private:
  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0, pos_ = 0;
};

// A compressed chunk as io::bloscFromStream / io::unzipFromStream read it:
// an int64 size, negative for `bytes` stored as they are.
void chunk(Walker& w, uint32_t compression, uint64_t bytes) {
  if (!(compression & (kZip | kBlosc))) return w.skip(bytes, "uncompressed values");
  const int64_t n = w.get<int64_t>("chunk size");
  if (n <= 0) {
    if (n == std::numeric_limits<int64_t>::min() || uint64_t(-n) != bytes)
      w.fail(fmt::format("stored chunk of {} bytes, expected {}", n, bytes));
    return w.skip(bytes, "stored chunk");
  }
  w.need(uint64_t(n), "compressed chunk");
  if (!(compression & kBlosc)) return w.skip(uint64_t(n), "zip chunk");
  // blosc_decompress takes its sizes from this header, not from the stream.
  if (uint64_t(n) < kBloscHeaderBytes) w.fail(fmt::format("blosc chunk of {} bytes", n));
  uint8_t h[kBloscHeaderBytes];
  w.read(h, sizeof h, "blosc header");
  uint32_t nbytes, blocksize, cbytes;
  std::memcpy(&nbytes, h + 4, 4);
  std::memcpy(&blocksize, h + 8, 4);
  std::memcpy(&cbytes, h + 12, 4);
  if (nbytes != bytes || blocksize > std::max<uint32_t>(nbytes, kBloscHeaderBytes) ||
      cbytes < kBloscHeaderBytes || cbytes > uint64_t(n))
    w.fail(fmt::format("blosc header of {} bytes for {}, block {}, in a chunk of {}: expected {} "
                       "bytes in the chunk",
                       cbytes, nbytes, blocksize, n, bytes));
  w.skip(uint64_t(n) - kBloscHeaderBytes, "blosc chunk");
}

// io::readCompressedValues: a flag, up to two inactive values, a selection
// mask, then the active (or all) values, as half when `half`.
void values(Walker& w, uint32_t compression, bool half, uint32_t count, uint32_t active,
            uint64_t mask_bytes) {
  const int8_t flag = w.get<int8_t>("mask compression flag");
  if (flag < 0 || flag > 6) w.fail(fmt::format("mask compression flag {}", int(flag)));
  if (flag == 2 || flag == 4 || flag == 5) w.skip(4, "inactive value");
  if (flag == 5) w.skip(4, "second inactive value");
  if (flag == 3 || flag == 4 || flag == 5) w.skip(mask_bytes, "selection mask");
  const uint32_t stored = (compression & kActiveMask) && flag != 6 ? active : count;
  if (half && stored == 0) return;  // io::HalfReader reads nothing then
  chunk(w, compression, uint64_t(stored) * (half ? 2 : 4));
}

template <size_t Bits>
std::bitset<Bits> mask(Walker& w, const char* what) {
  std::array<uint64_t, Bits / 64> words;
  w.read(words.data(), sizeof words, what);
  std::bitset<Bits> bits;
  for (size_t i = 0; i < words.size(); ++i)
    for (size_t b = 0; b < 64; ++b)
      if (words[i] >> b & 1) bits.set(i * 64 + b);
  return bits;
}

// An InternalNode's topology (Log2Dim 5 at the top, 4 below it); appends the
// active counts of its leaves, in the order their buffers follow.
template <size_t Log2Dim>
void internal_node(Walker& w, uint32_t compression, bool half, std::vector<uint16_t>& leaves) {
  constexpr size_t kBits = size_t(1) << (3 * Log2Dim);
  const std::bitset<kBits> children = mask<kBits>(w, "child mask");
  const std::bitset<kBits> active = mask<kBits>(w, "value mask");
  values(w, compression, half, uint32_t(kBits), uint32_t(active.count()), kBits / 8);
  for (size_t i = 0; i < kBits; ++i) {
    if (!children[i]) continue;
    if constexpr (Log2Dim == 5) {
      internal_node<4>(w, compression, half, leaves);
    } else {
      leaves.push_back(uint16_t(mask<512>(w, "leaf value mask").count()));
    }
  }
}

Coord coord(Walker& w, const char* what) {
  Coord c;
  w.read(c.data(), sizeof c, what);
  for (int32_t v : c)
    if (v < -kCoordLimit || v > kCoordLimit)
      w.fail(fmt::format("{} coordinate {} outside +-2^30", what, v));
  return c;
}

// The tree: topology up to the block offset, then the leaves' buffers.
void tree(Walker& w, uint32_t compression, bool half, uint64_t block_pos) {
  w.get<int32_t>("buffer count");
  w.get<float>("background");
  const uint32_t tiles = w.get<uint32_t>("root tile count");
  const uint32_t children = w.get<uint32_t>("root child count");
  constexpr uint64_t kTileBytes = 12 + 4 + 1, kChildBytes = 12 + 2 * 4096 + 1;
  if (tiles > w.left() / kTileBytes || children > w.left() / kChildBytes)
    w.fail(fmt::format("{} root tiles and {} children do not fit in the file", tiles, children));
  // The root table: a child at a tile's origin replaces the tile.
  std::map<Coord, std::vector<uint16_t>> table;
  for (uint32_t i = 0; i < tiles; ++i) {
    table[coord(w, "root tile")].clear();
    w.skip(5, "root tile value");
  }
  std::set<Coord> child_origins;
  for (uint32_t i = 0; i < children; ++i) {
    const Coord origin = coord(w, "root child");
    // OpenVDB would drop (and leak) the first child at a repeated origin.
    if (!child_origins.insert(origin).second) w.fail("two root children at one origin");
    std::vector<uint16_t> leaves;
    internal_node<5>(w, compression, half, leaves);
    table[origin] = std::move(leaves);
  }
  if (w.pos() != block_pos)
    w.fail(fmt::format("topology ends at byte {}, the grid's blocks start at {}", w.pos(),
                       block_pos));
  for (const auto& [origin, leaves] : table)
    for (uint16_t count : leaves) {
      if (mask<512>(w, "leaf value mask").count() != count)
        w.fail("a leaf's value mask differs between topology and buffers");
      values(w, compression, half, 512, count, 64);
    }
}

// A blosc block of DelayedLoadMetadata, written through
// compression::bloscCompress, which pads inputs below 128 bytes to 128.
void delayed_load_block(Walker& w, uint32_t block_bytes, uint64_t expected, const char* what) {
  w.need(block_bytes, what);
  if (block_bytes < kBloscHeaderBytes) w.fail(fmt::format("{} shorter than a blosc header", what));
  uint8_t h[kBloscHeaderBytes];
  w.read(h, sizeof h, "blosc header");
  uint32_t nbytes, cbytes;
  std::memcpy(&nbytes, h + 4, 4);
  std::memcpy(&cbytes, h + 12, 4);
  if (nbytes < expected || nbytes > std::max<uint64_t>(expected, 128) || cbytes > block_bytes)
    w.fail(fmt::format("{}: blosc header for {} bytes in {}, expected {}", what, nbytes, cbytes,
                       expected));
  w.skip(block_bytes - kBloscHeaderBytes, what);
}

// DelayedLoadMetadata::readValue: leaf count, a mask per leaf and optionally
// a compressed size per leaf, each blosc-compressed or stored.
void delayed_load(Walker& w, uint32_t bytes) {
  if (bytes == 0) return;
  const uint64_t start = w.pos();
  const uint32_t count = w.get<uint32_t>("delayed-load leaf count");
  if (count > w.size() / 64)  // a leaf takes at least its 64-byte mask
    w.fail(fmt::format("delayed-load metadata for {} leaves", count));
  const uint32_t mask_bytes = w.get<uint32_t>("delayed-load mask size");
  if (mask_bytes > 0)
    delayed_load_block(w, mask_bytes, count, "delayed-load masks");
  else
    w.skip(count, "delayed-load masks");
  const uint32_t size_bytes = w.get<uint32_t>("delayed-load sizes size");
  if (size_bytes != std::numeric_limits<uint32_t>::max()) {
    if (size_bytes > 0)
      delayed_load_block(w, size_bytes, uint64_t(count) * 8, "delayed-load sizes");
    else
      w.skip(uint64_t(count) * 8, "delayed-load sizes");
  }
  const uint64_t used = w.pos() - start;
  if (used < bytes) w.skip(bytes - used, "delayed-load padding");
}

// MetaMap::readMeta: registered fixed-size types must have their size (OpenVDB
// reads sizeof(T) whatever the file says), the rest are skipped as stored.
void metadata(Walker& w, const char* where) {
  const uint32_t count = w.get<uint32_t>("metadata count");
  if (count > w.left() / 12)
    w.fail(fmt::format("{} metadata count {} does not fit in the file", where, count));
  for (uint32_t i = 0; i < count; ++i) {
    const std::string name = w.string("metadata name");
    const std::string type = w.string("metadata type");
    const uint32_t bytes = w.get<uint32_t>("metadata size");
    if (type == "__delayedload") {
      delayed_load(w, bytes);
      continue;
    }
    if (type != "string" && openvdb::Metadata::isRegisteredType(type)) {
      const uint32_t fixed = openvdb::Metadata::createMetadata(type)->size();
      if (bytes != fixed)
        w.fail(fmt::format("{} metadata '{}' of type {} has {} bytes, expected {}", where, name,
                           type, bytes, fixed));
    }
    w.skip(bytes, "metadata value");
  }
}

// Archive::readHeader reads the UUID with a stream's >>, which skips white
// space: a UUID with a space or a line break in it would move OpenVDB one
// byte further than this walk, onto lengths nobody checked. Only the
// canonical form, 32 hex digits with hyphens after the 8th, 12th, 16th and
// 20th, is taken.
void uuid(Walker& w) {
  char text[36];
  w.read(text, sizeof(text), "UUID");
  for (int i = 0; i < 36; ++i) {
    const bool hyphen = i == 8 || i == 13 || i == 18 || i == 23;
    const bool ok = hyphen ? text[i] == '-' : std::isxdigit(static_cast<unsigned char>(text[i])) != 0;
    if (!ok) w.fail("expected a UUID of 32 hex digits and 4 hyphens");
  }
}

// Transform::read: a map type, then the map's fixed-size values.
void transform(Walker& w) {
  static const std::map<std::string, uint64_t> kMapBytes = {
      {"AffineMap", 128},       {"UnitaryMap", 128},         {"ScaleMap", 120},
      {"UniformScaleMap", 120}, {"TranslationMap", 24},      {"ScaleTranslateMap", 144},
      {"UniformScaleTranslateMap", 144}};
  const std::string type = w.string("transform type");
  const auto it = kMapBytes.find(type);
  if (it == kMapBytes.end())
    w.fail(fmt::format("transform '{}' (linear maps only)", type.substr(0, 64)));
  w.skip(it->second, "transform");
}

}  // namespace

void check_vdb_layout(const std::string& path) {
  Walker w(path);
  if (w.get<int64_t>("magic") != kMagic) w.fail("expected the magic \"VDB \"");
  const uint32_t version = w.get<uint32_t>("file format version");
  if (version < kOldestVersion || version > kNewestVersion)
    w.fail(fmt::format("file format version {}, expected {} to {}", version, kOldestVersion,
                       kNewestVersion));
  w.skip(8, "library version");
  if (w.get<char>("grid offsets flag") != 1) w.fail("expected a file with grid offsets");
  uuid(w);
  metadata(w, "file");
  const int32_t grids = w.get<int32_t>("grid count");
  constexpr uint64_t kDescriptorBytes = 3 * 4 + 3 * 8;
  if (grids < 0 || uint64_t(grids) > w.left() / kDescriptorBytes)
    w.fail(fmt::format("grid count {} does not fit in the file", grids));
  const std::string kHalf = "_HalfFloat";
  for (int32_t g = 0; g < grids; ++g) {
    const std::string name = w.string("grid name");
    std::string type = w.string("grid type");
    const bool half = type.size() > kHalf.size() &&
                      type.compare(type.size() - kHalf.size(), kHalf.size(), kHalf) == 0;
    if (half) type.resize(type.size() - kHalf.size());
    if (type != "Tree_float_5_4_3")
      w.fail(fmt::format("expected float grids, got a {} grid", type.substr(0, 64)));
    if (!w.string("instance parent").empty()) w.fail("grid instances are not read");
    const int64_t grid_pos = w.get<int64_t>("grid offset");
    const int64_t block_pos = w.get<int64_t>("block offset");
    const int64_t end_pos = w.get<int64_t>("end offset");
    if (grid_pos != int64_t(w.pos()) || block_pos < grid_pos || end_pos < block_pos ||
        uint64_t(end_pos) > w.size())
      w.fail(fmt::format("grid offsets {}, {}, {} out of order or past the end", grid_pos,
                         block_pos, end_pos));
    const uint32_t compression = w.get<uint32_t>("grid compression");
    if (compression & ~(kZip | kActiveMask | kBlosc))
      w.fail(fmt::format("compression flags 0x{:x}", compression));
    metadata(w, "grid");
    transform(w);
    tree(w, compression, half, uint64_t(block_pos));
    if (w.pos() != uint64_t(end_pos))
      w.fail(fmt::format("grid ends at byte {}, its end offset is {}", w.pos(), end_pos));
  }
}

}  // namespace skybake

// EXR reader through OpenEXR; the file shapes and header attributes are
// documented in exr.hpp.
#include "io/exr.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>

#include "core/error.hpp"
#include "io/exr_attributes.hpp"
#include "io/exr_format.hpp"
#include "io/shape_text.hpp"
#include "io/size_math.hpp"

namespace skybake {

namespace {

using PartShape = ShapeText;

// What the reader needs of one part's header, sizes in 64 bits (a forged data
// window can span more than INT_MAX).
struct PartInfo {
  const Imf::Header* header = nullptr;
  int64_t min_x = 0, min_y = 0, width = 0, height = 0;
  int64_t channels = 0;
  bool deep = false;
  bool subsampled = false;
};

PartInfo part_info(const Imf::Header& h) {
  PartInfo p;
  p.header = &h;
  const Imath::Box2i& dw = h.dataWindow();
  p.min_x = dw.min.x;
  p.min_y = dw.min.y;
  p.width = int64_t(dw.max.x) - dw.min.x + 1;
  p.height = int64_t(dw.max.y) - dw.min.y + 1;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
    ++p.channels;
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1) p.subsampled = true;
  }
  p.deep = h.hasType() && (h.type() == Imf::DEEPSCANLINE || h.type() == Imf::DEEPTILE);
  return p;
}

std::string string_attribute(const Imf::Header& h, const std::string& name,
                             const std::string& fallback = "") {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
  return a ? a->value() : fallback;
}

int int_attribute(const Imf::Header& h, const std::string& name) {
  const auto* a = h.findTypedAttribute<Imf::IntAttribute>(name);
  return a ? a->value() : 0;
}

bool has_channel(const Imf::Header& h, const std::string& name) {
  return h.channels().findChannel(name) != nullptr;
}

// The name texture channel `name` has in part `h`: prefixed with the part's
// name where the part holds it so (exr_part_channels), else `name` itself.
std::string file_channel(const Imf::Header& h, const std::string& name) {
  if (h.hasName() && has_channel(h, h.name() + "." + name)) return h.name() + "." + name;
  return name;
}

// A foreign file's channels, without the part's name as prefix: EXR stores
// them sorted by name; R, G, B, A come first (in that order), then the
// others in file order.
std::vector<std::string> file_channels(const Imf::Header& h) {
  const std::string prefix = h.hasName() ? h.name() + "." : "";
  std::vector<std::string> out;
  for (const char* rgba : {"R", "G", "B", "A"})
    if (has_channel(h, file_channel(h, rgba))) out.push_back(rgba);
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
    std::string name = it.name();
    if (!prefix.empty() && name.rfind(prefix, 0) == 0) name = name.substr(prefix.size());
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  return out;
}

// Every size below comes from the file: products are taken in 64 bits and
// saturate (io/size_math.hpp).
using sizes::kU64Max;
using sizes::mul_saturated;

// Refuses, before any pixel is allocated, a file whose parts would decode to
// more float32 bytes than kMaxExrExpansion times the file's size (with a
// floor of kExrExpansionFloor): EXR's lossless codecs compress at most about
// 1000:1 (deflate), so such a header cannot describe the pixels that follow.
constexpr uint64_t kMaxExrExpansion = 4096;
constexpr uint64_t kExrExpansionFloor = uint64_t(64) << 20;
constexpr uint64_t kMaxExrDecodedBytes = uint64_t(16) << 30;

void check_decoded_size(const std::string& path, const std::vector<PartInfo>& specs) {
  uint64_t decoded = 0;
  for (size_t i = 0; i < specs.size(); ++i) {
    const PartInfo& s = specs[i];
    if (s.width < 1 || s.height < 1 || s.width > std::numeric_limits<int>::max() ||
        s.height > std::numeric_limits<int>::max() || s.channels < 1)
      throw IoError(fmt::format("{}: part {}: expected a 2D image with channels, got {}x{}x1 "
                                "with {} channels",
                                path, i, s.width, s.height, s.channels));
    if (s.deep) throw IoError(fmt::format("{}: part {}: expected flat pixels, got deep data", path, i));
    if (s.subsampled)
      throw IoError(fmt::format("{}: part {}: expected full-resolution channels, got subsampled ones",
                                path, i));
    const uint64_t part = mul_saturated(
        mul_saturated(mul_saturated(uint64_t(s.width), uint64_t(s.height)), uint64_t(s.channels)),
        sizeof(float));
    decoded = sizes::add_saturated(decoded, part);
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw IoError(fmt::format("{}: cannot stat: {}", path, std::strerror(errno)));
  const uint64_t file_size = uint64_t(st.st_size);
  const uint64_t allowed =
      std::min(kMaxExrDecodedBytes,
               std::max(kExrExpansionFloor, mul_saturated(file_size, kMaxExrExpansion)));
  if (decoded > allowed)
    throw IoError(fmt::format(
        "{}: header sizes decode to {} bytes of float32 pixels from a {}-byte file; the limit "
        "is {} times the file size (at least {} MiB, at most {} GiB)",
        path, decoded == kU64Max ? std::string("more than 2^64") : std::to_string(decoded),
        file_size, kMaxExrExpansion, kExrExpansionFloor >> 20, kMaxExrDecodedBytes >> 30));
}

// What reading takes at once, checked before the texture is allocated: the
// texture, plus the atlas image beside it (its slices are copied out of it;
// other parts are decoded straight into their slab of the texture).
void check_exr_budget(const std::string& path, const PartShape& shape, size_t channels,
                      const PartInfo& atlas, bool is_atlas, uint64_t budget) {
  const uint64_t texels = mul_saturated(
      mul_saturated(uint64_t(shape.width), uint64_t(shape.height)),
      mul_saturated(uint64_t(shape.depth), uint64_t(shape.layers)));
  const uint64_t bytes = mul_saturated(texels, uint64_t(channels) * sizeof(float));
  const uint64_t atlas_bytes =
      is_atlas ? mul_saturated(mul_saturated(uint64_t(atlas.width), uint64_t(atlas.height)),
                               uint64_t(channels) * sizeof(float))
               : 0;
  check_read_budget(path, sizes::add_saturated(bytes, atlas_bytes), budget,
                    fmt::format("{}x{}x{}x{} float32 texels with {} channel{}{}", shape.width,
                                shape.height, shape.depth, shape.layers, channels,
                                channels == 1 ? "" : "s",
                                is_atlas ? ", and the slice atlas they are cut from" : ""));
}

// Reads one part as float32 with the channels in `channels` order into
// `out`, room for width x height x channels values.
void read_part_into(const std::string& path, Imf::MultiPartInputFile& in, int part,
                    const PartInfo& info, const std::vector<std::string>& channels, float* out) {
  std::vector<std::string> names;
  for (const std::string& name : channels) {
    names.push_back(file_channel(*info.header, name));
    if (!has_channel(*info.header, names.back()))
      throw IoError(
          fmt::format("{}: expected a channel '{}' in part {}, got none", path, name, part));
  }
  Imf::InputPart input(in, part);
  input.setFrameBuffer(exr_frame_buffer(names, out, info.width, info.min_x, info.min_y));
  input.readPixels(int(info.min_y), int(info.min_y + info.height - 1));
}

void expect_part_size(const std::string& path, const PartInfo& spec, int part, int64_t width,
                      int64_t height) {
  if (spec.width != width || spec.height != height)
    throw IoError(fmt::format("{}: expected part {} of {}x{}, got {}x{}", path, part, width, height,
                              spec.width, spec.height));
}

// The atlas layout from its int attributes (exr.hpp), checked against
// skybake:shape and the image: slice_count x slice_width x slice_height is
// the volume, atlas_columns x atlas_rows cells hold exactly slice_count
// slices, and the image is that many slices wide and high. Returns columns.
int atlas_columns(const std::string& path, const Imf::Header& h, const PartShape& shape) {
  const int columns = int_attribute(h, kExrPrefix + "atlas_columns");
  const int rows = int_attribute(h, kExrPrefix + "atlas_rows");
  const int count = int_attribute(h, kExrPrefix + "slice_count");
  const int width = int_attribute(h, kExrPrefix + "slice_width");
  const int height = int_attribute(h, kExrPrefix + "slice_height");
  if (shape.layers != 1)
    throw IoError(fmt::format("{}: expected 1 layer in an atlas (skybake:shape), got {}", path,
                              shape.layers));
  if (count != shape.depth || width != shape.width || height != shape.height)
    throw IoError(fmt::format(
        "{}: expected skybake:slice_count, slice_width, slice_height {}, {}, {} (skybake:shape), "
        "got {}, {}, {}",
        path, shape.depth, shape.width, shape.height, count, width, height));
  if (columns < 1 || rows < 1 || int64_t(columns) * rows != count)
    throw IoError(fmt::format("{}: expected an atlas of {} cells (skybake:atlas_columns x "
                              "skybake:atlas_rows), got {}x{}",
                              path, count, columns, rows));
  const PartInfo info = part_info(h);
  expect_part_size(path, info, 0, int64_t(columns) * width, int64_t(rows) * height);
  return columns;
}

// OpenEXR allocates every attribute's declared size before it reads the
// value (a 731-byte file declaring a 1.8 GB string took 2 GB and 15 s): the
// headers are walked first, each attribute's size against the bytes left.
// Layout (openexr.com, "OpenEXR File Layout"): magic, version and flags, then
// one header (several for multi-part, ended by an empty one), each a list of
// name\0 type\0 int32 size, value, ended by \0.
void check_header_sizes(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw IoError(fmt::format("{}: expected a regular file", path));
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const int64_t size = int64_t(in.tellg());
  in.seekg(0);
  const auto fail = [&](const std::string& rule) {
    throw IoError(fmt::format("{}: not an EXR skybake can read safely: {}", path, rule));
  };
  uint32_t magic = 0, version = 0;
  in.read(reinterpret_cast<char*>(&magic), 4);
  in.read(reinterpret_cast<char*>(&version), 4);
  if (!in || magic != 20000630) fail("expected the EXR magic number");
  const bool multipart = version & 0x1000;
  const size_t max_name = (version & 0x400) ? 255 : 31;
  const auto name = [&](const char* what) {
    std::string s;
    for (int c; (c = in.get()) != 0;) {
      if (c == EOF) fail(fmt::format("the file ends inside a header ({})", what));
      if (s.size() == max_name) fail(fmt::format("{} longer than {} characters", what, max_name));
      s += char(c);
    }
    return s;
  };
  for (int part = 0;; ++part) {
    int attributes = 0;
    for (std::string attribute; !(attribute = name("attribute name")).empty(); ++attributes) {
      name("attribute type");
      int32_t bytes = 0;
      in.read(reinterpret_cast<char*>(&bytes), 4);
      const int64_t left = size - int64_t(in.tellg());
      if (!in || bytes < 0 || bytes > left)
        fail(fmt::format("attribute '{}' of part {} declares {} bytes, {} remain", attribute, part,
                         bytes, in ? left : 0));
      in.seekg(bytes, std::ios::cur);
    }
    if (!multipart || attributes == 0) break;
  }
}

Texture read_exr_file(const std::string& path, ExrShape shape_from, uint64_t budget) {
  check_header_sizes(path);
  Imf::MultiPartInputFile in(path.c_str(), exr_threads());
  std::vector<PartInfo> specs;
  for (int s = 0; s < in.parts(); ++s) specs.push_back(part_info(in.header(s)));
  if (specs.empty()) throw IoError(fmt::format("{}: expected at least one part, got none", path));
  // Every skybake:* attribute is checked against the parts' real sizes, and
  // those against the file size, before the texture is allocated.
  check_decoded_size(path, specs);
  const PartInfo& head_info = specs.at(0);
  const Imf::Header& head = *head_info.header;

  PartShape shape{int(head_info.width), int(head_info.height), 1, int(specs.size())};
  const bool recorded = shape_from == ExrShape::recorded;
  const std::string shape_text = recorded ? string_attribute(head, kExrPrefix + "shape") : "";
  if (!shape_text.empty()) {
    const std::optional<PartShape> parsed =
        parse_shape_text(shape_text, std::numeric_limits<int>::max());
    if (!parsed)
      throw IoError(fmt::format(
          "{}: expected skybake:shape of the form WxHxDxL with sizes from 1 to {}, got '{}'", path,
          std::numeric_limits<int>::max(), shape_text));
    shape = *parsed;
  }
  const std::string stored = specs.size() > 1 ? "layers" : "image";
  const std::string layout = recorded ? string_attribute(head, kExrPrefix + "layout", stored) : stored;
  const std::string channel_text = string_attribute(head, kExrPrefix + "channels");
  const std::vector<std::string> channels =
      channel_text.empty() ? file_channels(head) : split_exr_channels(channel_text);
  for (size_t c = 0; c < channels.size(); ++c)
    if (!has_channel(head, file_channel(head, channels[c])) ||
        std::find(channels.begin(), channels.begin() + c, channels[c]) != channels.begin() + c)
      throw IoError(fmt::format(
          "{}: expected skybake:channels to name distinct channels of the file, got '{}'", path,
          channels[c]));
  int columns = 0;
  if (layout == "atlas") {
    columns = atlas_columns(path, head, shape);
  } else {
    const uint64_t parts = uint64_t(shape.depth) * uint64_t(shape.layers);
    if (specs.size() != parts)
      throw IoError(fmt::format("{}: expected {} parts for a {}x{}x{}x{} texture, got {}", path,
                                parts, shape.width, shape.height, shape.depth, shape.layers,
                                specs.size()));
    for (size_t i = 0; i < specs.size(); ++i)
      expect_part_size(path, specs[i], int(i), shape.width, shape.height);
  }
  check_exr_budget(path, shape, channels.size(), head_info, layout == "atlas", budget);
  Texture tex(shape.width, shape.height, shape.depth, shape.layers, channels);
  for (auto it = head.begin(); it != head.end(); ++it) {
    const std::string name = it.name();
    if (name.rfind(kExrPrefix, 0) != 0) continue;
    const std::string key = name.substr(kExrPrefix.size());
    if (is_reserved_exr_key(key)) continue;
    if (std::optional<MetaValue> value = typed_attribute(it.attribute())) tex.metadata[key] = *value;
  }

  if (layout == "atlas") {
    const size_t nc = tex.channels.size(), atlas_width = size_t(columns) * tex.width;
    std::vector<float> atlas(size_t(head_info.width) * size_t(head_info.height) * nc);
    read_part_into(path, in, 0, head_info, tex.channels, atlas.data());
    for (int z = 0; z < tex.depth; ++z) {
      const size_t x0 = size_t(z % columns) * tex.width, y0 = size_t(z / columns) * tex.height;
      for (int y = 0; y < tex.height; ++y) {
        const float* src = &atlas[((y0 + y) * atlas_width + x0) * nc];
        std::copy(src, src + tex.width * nc, tex.texel(0, y, z, 0));
      }
    }
    return tex;
  }
  // Parts are slices (layers == 1) or layers (depth == 1), each of the
  // texture's width and height: the part index is the slab index of the
  // texture layout, and each part is decoded straight into its slab.
  const size_t slab = size_t(tex.width) * size_t(tex.height) * tex.channels.size();
  for (size_t i = 0; i < specs.size(); ++i)
    read_part_into(path, in, int(i), specs[i], tex.channels, tex.data.data() + i * slab);
  return tex;
}

}  // namespace

ExrLayout read_exr_layout(const std::string& path) {
  try {
    check_header_sizes(path);
    Imf::MultiPartInputFile in(path.c_str(), exr_threads());
    const Imf::Header& h = in.header(0);
    ExrLayout out;
    out.parts = in.parts();
    out.layout = string_attribute(h, kExrPrefix + "layout", out.parts > 1 ? "layers" : "image");
    out.atlas_columns = int_attribute(h, kExrPrefix + "atlas_columns");
    out.atlas_rows = int_attribute(h, kExrPrefix + "atlas_rows");
    out.slice_count = int_attribute(h, kExrPrefix + "slice_count");
    return out;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(fmt::format("{}: cannot read EXR: {}", path, e.what()));
  }
}

Texture read_exr(const std::string& path, ExrShape shape, uint64_t budget) {
  try {
    return read_exr_file(path, shape, budget);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // OpenEXR's Iex exceptions, bad_alloc
    throw IoError(fmt::format("{}: cannot read EXR: {}", path, e.what()));
  }
}

}  // namespace skybake

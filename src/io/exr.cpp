// EXR writer and reader through OpenImageIO; the file shapes and header
// attributes are documented in exr.hpp.
#include "io/exr.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

namespace {

const std::string kPrefix = "skybake:";
// A fixed stamp: OpenImageIO writes the current time when DateTime is unset
// (and also when it is erased), which would break byte-identical output.
const char* const kFixedDateTime = "1970:01:01 00:00:00";
const char* const kReservedKeys[] = {"shape",      "channels",    "layout",       "atlas_columns",
                                     "atlas_rows", "slice_width", "slice_height", "slice_depth"};
// Half values at or above this magnitude round to Inf (65504 + half an ulp).
constexpr float kHalfOverflow = 65520.0f;

bool is_reserved(const std::string& key) {
  for (const char* r : kReservedKeys)
    if (key == r) return true;
  return false;
}

std::string shape_attribute(const Texture& tex) {
  return fmt::format("{}x{}x{}x{}", tex.width, tex.height, tex.depth, tex.layers);
}

std::string join_channels(const std::vector<std::string>& channels) {
  std::string s;
  for (size_t i = 0; i < channels.size(); ++i) s += (i ? "," : "") + channels[i];
  return s;
}

std::vector<std::string> split_channels(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = s.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(s.substr(start, comma - start));
  out.push_back(s.substr(start));
  return out;
}

// Refuses what the file could not represent, before anything is created.
void check_writable(const std::string& path, const Texture& tex, ExrPrecision precision) {
  if (tex.width < 1 || tex.height < 1 || tex.depth < 1 || tex.layers < 1 || tex.channels.empty())
    throw IoError(fmt::format("{}: expected a non-empty texture, got {} with {} channels", path,
                              tex.shape_string(), tex.channels.size()));
  if (tex.data.size() != tex.texel_count() * tex.channels.size())
    throw Error(fmt::format("{}: expected {} floats for {}, got {}", path,
                            tex.texel_count() * tex.channels.size(), tex.shape_string(),
                            tex.data.size()));
  if (tex.is_volume() && tex.is_array())
    throw IoError(fmt::format("{}: expected a volume or a 2D array, got both ({})", path,
                              tex.shape_string()));
  for (const std::string& name : tex.channels)
    if (name.empty() || name.find(',') != std::string::npos)
      throw IoError(fmt::format("{}: expected channel names without commas, got '{}'", path, name));
  for (const auto& [key, value] : tex.metadata)
    if (is_reserved(key))
      throw Error(fmt::format("{}: expected a metadata key other than the reserved '{}{}'", path,
                              kPrefix, key));
  check_finite(tex, path);
  if (precision == ExrPrecision::half)
    for (float v : tex.data)
      if (std::fabs(v) >= kHalfOverflow)
        throw IoError(fmt::format(
            "{}: expected values below {} in magnitude for half output, got {}; use float32", path,
            kHalfOverflow, v));
}

// The header every part shares: channels, compression, fixed DateTime,
// metadata and shape.
OIIO::ImageSpec base_spec(const Texture& tex, int width, int height, ExrPrecision precision,
                          const std::string& layout) {
  const OIIO::TypeDesc format =
      precision == ExrPrecision::half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(width, height, tex.channel_count(), format);
  spec.channelnames = tex.channels;
  spec.alpha_channel = tex.channel_index("A");
  spec.z_channel = -1;
  spec.attribute("compression", "zip");
  spec.attribute("DateTime", kFixedDateTime);
  for (const auto& [key, value] : tex.metadata) spec.attribute(kPrefix + key, value);
  spec.attribute(kPrefix + "shape", shape_attribute(tex));
  spec.attribute(kPrefix + "channels", join_channels(tex.channels));
  spec.attribute(kPrefix + "layout", layout);
  return spec;
}

// Copies the slices of a volume into an atlas image (zero in unused cells).
std::vector<float> make_atlas(const Texture& tex, int columns, int rows) {
  const size_t nc = tex.channels.size();
  const size_t atlas_width = size_t(columns) * tex.width;
  std::vector<float> atlas(atlas_width * size_t(rows) * tex.height * nc, 0.0f);
  for (int z = 0; z < tex.depth; ++z) {
    const size_t x0 = size_t(z % columns) * tex.width, y0 = size_t(z / columns) * tex.height;
    for (int y = 0; y < tex.height; ++y) {
      const float* src = tex.texel(0, y, z, 0);
      std::copy(src, src + tex.width * nc, &atlas[((y0 + y) * atlas_width + x0) * nc]);
    }
  }
  return atlas;
}

// Writes the given parts (one spec and one pixel pointer each, float32 with
// channels interleaved) as a single- or multi-part EXR.
void write_parts(const std::string& path, std::vector<OIIO::ImageSpec>& specs,
                 const std::vector<const float*>& pixels) {
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out)
    throw IoError(fmt::format("{}: cannot create an EXR writer: {}", path, OIIO::geterror()));
  bool ok = specs.size() == 1 ? out->open(path, specs[0])
                              : out->open(path, int(specs.size()), specs.data());
  for (size_t i = 0; ok && i < specs.size(); ++i) {
    if (i > 0) ok = out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage);
    ok = ok && out->write_image(OIIO::TypeDesc::FLOAT, pixels[i]);
  }
  ok = out->close() && ok;
  if (!ok) {
    const std::string message = out->geterror();
    out.reset();
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: cannot write EXR: {}", path, message));
  }
}

}  // namespace

int exr_atlas_columns(int depth) {
  int columns = 1;
  while (columns * columns < depth) ++columns;
  return columns;
}

void write_exr(const std::string& path, const Texture& tex, ExrPrecision precision,
               ExrVolumeLayout layout) {
  check_writable(path, tex, precision);
  std::vector<OIIO::ImageSpec> specs;
  std::vector<const float*> pixels;
  std::vector<float> atlas;
  if (tex.is_volume() && layout == ExrVolumeLayout::atlas) {
    const int columns = exr_atlas_columns(tex.depth);
    const int rows = (tex.depth + columns - 1) / columns;
    OIIO::ImageSpec spec =
        base_spec(tex, columns * tex.width, rows * tex.height, precision, "atlas");
    spec.attribute(kPrefix + "atlas_columns", columns);
    spec.attribute(kPrefix + "atlas_rows", rows);
    spec.attribute(kPrefix + "slice_width", tex.width);
    spec.attribute(kPrefix + "slice_height", tex.height);
    spec.attribute(kPrefix + "slice_depth", tex.depth);
    atlas = make_atlas(tex, columns, rows);
    specs.push_back(spec);
    pixels.push_back(atlas.data());
  } else if (tex.is_volume() || tex.is_array()) {
    const bool volume = tex.is_volume();
    const int parts = volume ? tex.depth : tex.layers;
    for (int i = 0; i < parts; ++i) {
      specs.push_back(
          base_spec(tex, tex.width, tex.height, precision, volume ? "slices" : "layers"));
      specs.back().attribute("oiio:subimagename",
                             fmt::format("{}{}", volume ? "slice" : "layer", i));
      pixels.push_back(volume ? tex.texel(0, 0, i, 0) : tex.texel(0, 0, 0, i));
    }
  } else {
    specs.push_back(base_spec(tex, tex.width, tex.height, precision, "image"));
    pixels.push_back(tex.data.data());
  }
  write_parts(path, specs, pixels);
}

namespace {

struct Shape {
  int width = 0, height = 0, depth = 1, layers = 1;
};

// Every size below comes from the file: products are taken in 64 bits and
// saturate instead of wrapping, so no forged header can announce a small total.
constexpr uint64_t kU64Max = std::numeric_limits<uint64_t>::max();
uint64_t mul_saturated(uint64_t a, uint64_t b) {
  return a != 0 && b > kU64Max / a ? kU64Max : a * b;
}

// "WxHxDxL", four integers from 1 to INT_MAX, or nullopt.
std::optional<Shape> parse_shape(const std::string& text) {
  int values[4];
  const char* p = text.c_str();
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && *p++ != 'x') return std::nullopt;
    if (*p < '0' || *p > '9') return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(p, &end, 10);
    if (errno != 0 || v < 1 || v > std::numeric_limits<int>::max()) return std::nullopt;
    values[i] = int(v);
    p = end;
  }
  if (*p != '\0') return std::nullopt;
  return Shape{values[0], values[1], values[2], values[3]};
}

// Refuses, before any pixel is allocated, a file whose parts would decode to
// more float32 bytes than kMaxExrExpansion times the file's size (with a
// floor of kExrExpansionFloor): EXR's lossless codecs compress at most about
// 1000:1 (deflate), so such a header cannot describe the pixels that follow.
constexpr uint64_t kMaxExrExpansion = 4096;
constexpr uint64_t kExrExpansionFloor = uint64_t(64) << 20;
constexpr uint64_t kMaxExrDecodedBytes = uint64_t(16) << 30;

void check_decoded_size(const std::string& path, const std::vector<OIIO::ImageSpec>& specs) {
  uint64_t decoded = 0;
  for (size_t i = 0; i < specs.size(); ++i) {
    const OIIO::ImageSpec& s = specs[i];
    if (s.width < 1 || s.height < 1 || s.depth != 1 || s.nchannels < 1)
      throw IoError(fmt::format("{}: part {}: expected a 2D image with channels, got {}x{}x{} "
                                "with {} channels",
                                path, i, s.width, s.height, s.depth, s.nchannels));
    if (s.deep) throw IoError(fmt::format("{}: part {}: expected flat pixels, got deep data", path, i));
    const uint64_t part = mul_saturated(
        mul_saturated(mul_saturated(uint64_t(s.width), uint64_t(s.height)), uint64_t(s.nchannels)),
        sizeof(float));
    decoded = part > kU64Max - decoded ? kU64Max : decoded + part;
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

// Reads one part as float32 with the channels in `channels` order.
std::vector<float> read_part(const std::string& path, OIIO::ImageInput& in, int part,
                             const std::vector<std::string>& channels) {
  if (!in.seek_subimage(part, 0))
    throw IoError(fmt::format("{}: expected a part {}, got none", path, part));
  const OIIO::ImageSpec& spec = in.spec();
  std::vector<float> file(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in.read_image(part, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, file.data()))
    throw IoError(fmt::format("{}: cannot read part {}: {}", path, part, in.geterror()));
  std::vector<int> from;
  for (const std::string& name : channels) {
    const int c = spec.channelindex(name);
    if (c < 0)
      throw IoError(
          fmt::format("{}: expected a channel '{}' in part {}, got none", path, name, part));
    from.push_back(c);
  }
  const size_t texels = size_t(spec.width) * spec.height, nc = channels.size();
  std::vector<float> out(texels * nc);
  for (size_t t = 0; t < texels; ++t)
    for (size_t c = 0; c < nc; ++c) out[t * nc + c] = file[t * spec.nchannels + from[c]];
  return out;
}

void expect_part_size(const std::string& path, const OIIO::ImageSpec& spec, int part,
                      int64_t width, int64_t height) {
  if (spec.width != width || spec.height != height)
    throw IoError(fmt::format("{}: expected part {} of {}x{}, got {}x{}", path, part, width, height,
                              spec.width, spec.height));
}

}  // namespace

Texture read_exr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw IoError(fmt::format("{}: cannot read EXR: {}", path, OIIO::geterror()));
  std::vector<OIIO::ImageSpec> specs;
  for (int s = 0; in->seek_subimage(s, 0); ++s) specs.push_back(in->spec());
  if (specs.empty()) throw IoError(fmt::format("{}: expected at least one part, got none", path));
  // Every skybake:* attribute is checked against the parts' real sizes, and
  // those against the file size, before the texture is allocated.
  check_decoded_size(path, specs);
  const OIIO::ImageSpec& head = specs.at(0);

  Shape shape{head.width, head.height, 1, int(specs.size())};
  const std::string shape_text = head.get_string_attribute(kPrefix + "shape");
  if (!shape_text.empty()) {
    const std::optional<Shape> parsed = parse_shape(shape_text);
    if (!parsed)
      throw IoError(fmt::format(
          "{}: expected skybake:shape of the form WxHxDxL with sizes from 1 to {}, got '{}'", path,
          std::numeric_limits<int>::max(), shape_text));
    shape = *parsed;
  }
  const std::string layout =
      head.get_string_attribute(kPrefix + "layout", specs.size() > 1 ? "layers" : "image");
  const std::string channel_text = head.get_string_attribute(kPrefix + "channels");
  const std::vector<std::string> channels =
      channel_text.empty() ? head.channelnames : split_channels(channel_text);
  for (size_t c = 0; c < channels.size(); ++c)
    if (head.channelindex(channels[c]) < 0 ||
        std::find(channels.begin(), channels.begin() + c, channels[c]) != channels.begin() + c)
      throw IoError(fmt::format(
          "{}: expected skybake:channels to name distinct channels of the file, got '{}'", path,
          channels[c]));
  int columns = 0;
  if (layout == "atlas") {
    columns = head.get_int_attribute(kPrefix + "atlas_columns");
    const int rows = head.get_int_attribute(kPrefix + "atlas_rows");
    if (shape.layers != 1)
      throw IoError(fmt::format("{}: expected 1 layer in an atlas (skybake:shape), got {}", path,
                                shape.layers));
    if (columns < 1 || rows < 1 || int64_t(columns) * rows < shape.depth)
      throw IoError(fmt::format("{}: expected an atlas of at least {} cells, got {}x{}", path,
                                shape.depth, columns, rows));
    expect_part_size(path, head, 0, int64_t(columns) * shape.width,
                     int64_t(rows) * shape.height);
  } else {
    const uint64_t parts = uint64_t(shape.depth) * uint64_t(shape.layers);
    if (specs.size() != parts)
      throw IoError(fmt::format("{}: expected {} parts for a {}x{}x{}x{} texture, got {}", path,
                                parts, shape.width, shape.height, shape.depth, shape.layers,
                                specs.size()));
    for (size_t i = 0; i < specs.size(); ++i)
      expect_part_size(path, specs[i], int(i), shape.width, shape.height);
  }
  Texture tex(shape.width, shape.height, shape.depth, shape.layers, channels);
  for (const OIIO::ParamValue& p : head.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind(kPrefix, 0) != 0 || p.type() != OIIO::TypeString) continue;
    const std::string key = name.substr(kPrefix.size());
    if (!is_reserved(key)) tex.metadata[key] = p.get_string();
  }

  if (layout == "atlas") {
    const std::vector<float> atlas = read_part(path, *in, 0, tex.channels);
    const size_t nc = tex.channels.size(), atlas_width = size_t(columns) * tex.width;
    for (int z = 0; z < tex.depth; ++z) {
      const size_t x0 = size_t(z % columns) * tex.width, y0 = size_t(z / columns) * tex.height;
      for (int y = 0; y < tex.height; ++y) {
        const float* src = &atlas[((y0 + y) * atlas_width + x0) * nc];
        std::copy(src, src + tex.width * nc, tex.texel(0, y, z, 0));
      }
    }
    return tex;
  }
  for (size_t i = 0; i < specs.size(); ++i) {
    const std::vector<float> part = read_part(path, *in, int(i), tex.channels);
    // Parts are slices (layers == 1) or layers (depth == 1): either way the
    // part index is the slab index of the texture layout.
    std::copy(part.begin(), part.end(), tex.data.begin() + i * part.size());
  }
  return tex;
}

}  // namespace skybake

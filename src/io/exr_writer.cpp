// EXR writer through OpenEXR; the file shapes and header attributes are
// documented in exr.hpp.
#include "io/exr.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <half.h>
#include <fmt/format.h>

#include "core/error.hpp"
#include "io/exr_attributes.hpp"
#include "io/exr_format.hpp"

namespace skybake {

namespace {

// Half values at or above this magnitude round to Inf (65504 + half an ulp).
constexpr float kHalfOverflow = 65520.0f;
std::string shape_attribute(const Texture& tex) {
  return fmt::format("{}x{}x{}x{}", tex.width, tex.height, tex.depth, tex.layers);
}
// Refuses what the file could not represent, before anything is created.
void check_writable(const std::string& path, const Texture& tex, ExrPrecision precision,
                    FiniteCheck finite) {
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
    if (is_reserved_exr_key(key))
      throw Error(fmt::format("{}: expected a metadata key other than the reserved '{}{}'", path,
                              kExrPrefix, key));
  if (finite == FiniteCheck::run) check_finite(tex, path);
  if (precision == ExrPrecision::half)
    for (float v : tex.data)
      if (std::fabs(v) >= kHalfOverflow)
        throw IoError(fmt::format(
            "{}: expected values below {} in magnitude for half output, got {}; use float32", path,
            kHalfOverflow, v));
}

Imf::Compression imf_compression(ExrCompression c) {
  switch (c) {
    case ExrCompression::none: return Imf::NO_COMPRESSION;
    case ExrCompression::zip: return Imf::ZIP_COMPRESSION;
    case ExrCompression::zips: return Imf::ZIPS_COMPRESSION;
    case ExrCompression::piz: return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}
// The threads of a file written with `header`: none when it is not
// compressed. Each line block is then a copy of its scanlines, and handing
// it to the pool (a task and a semaphore post per scanline) costs more than
// the copy; the bytes are the same either way.
int exr_write_threads(const Imf::Header& header) {
  return header.compression() == Imf::NO_COMPRESSION ? 0 : exr_threads();
}

// The header every part shares: channels, compression, metadata and shape.
// A part of a multi-part file is named `part`, its channels prefixed with it.
Imf::Header base_header(const Texture& tex, int width, int height, ExrPrecision precision,
                        const std::string& layout, const std::string& part = "") {
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  if (!part.empty()) header.setName(part);
  const Imf::PixelType type = precision == ExrPrecision::half ? Imf::HALF : Imf::FLOAT;
  for (const std::string& name : exr_part_channels(part, tex.channels))
    header.channels().insert(name, Imf::Channel(type));
  for (const auto& [key, value] : tex.metadata) insert_typed_attribute(header, kExrPrefix + key, value);
  header.insert(kExrPrefix + "shape", Imf::StringAttribute(shape_attribute(tex)));
  header.insert(kExrPrefix + "channels", Imf::StringAttribute(join_exr_channels(tex.channels)));
  header.insert(kExrPrefix + "layout", Imf::StringAttribute(layout));
  add_exr_chromaticities(header, tex.metadata);
  return header;
}

// The frame buffer of one part to write, or of its `rows` scanlines from
// `min_y` (all of them by default); half parts are rounded here (Imath's
// float-to-half rounds to nearest even) into `halves`.
Imf::FrameBuffer write_buffer(const Imf::Header& header, const std::vector<std::string>& channels,
                              const float* pixels, std::vector<half>& halves, int64_t min_y = 0,
                              int64_t rows = -1) {
  const Imath::Box2i& dw = header.dataWindow();
  const int64_t width = dw.max.x + 1;
  if (rows < 0) rows = dw.max.y + 1;
  if (header.channels().begin().channel().type != Imf::HALF)
    return exr_frame_buffer(channels, pixels, width, 0, min_y);
  halves.resize(size_t(width) * size_t(rows) * channels.size());
  for (size_t i = 0; i < halves.size(); ++i) halves[i] = half(pixels[i]);
  return exr_frame_buffer(channels, halves.data(), width, 0, min_y);
}

// Runs `write`; what OpenEXR throws removes the partial file and becomes
// "<path>: cannot write EXR: <reason>".
template <class Write>
void write_or_remove(const std::string& path, Write write) {
  try {
    write();
  } catch (const std::exception& e) {
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: cannot write EXR: {}", path, e.what()));
  }
}

// Writes a volume as an atlas image of columns x rows cells, one row of
// cells (tex.height scanlines) at a time: the slice rows behind it are
// copied into one reused band, never the whole atlas (a fresh copy of the
// volume, zero-filled first). Scanlines go out in the same order, so the
// file is the same.
void write_atlas(const std::string& path, const Imf::Header& header, const Texture& tex,
                 int columns, int rows) {
  const size_t nc = tex.channels.size(), slice_row = size_t(tex.width) * nc;
  const size_t atlas_width = size_t(columns) * size_t(tex.width);
  std::vector<float> band(atlas_width * size_t(tex.height) * nc);
  std::vector<half> halves;
  write_or_remove(path, [&] {
    Imf::OutputFile out(path.c_str(), header, exr_write_threads(header));
    for (int r = 0; r < rows; ++r) {
      for (int k = 0; k < columns; ++k)
        for (int y = 0; y < tex.height; ++y) {
          const float* src = tex.texel(0, y, r * columns + k, 0);
          std::copy(src, src + slice_row, &band[(size_t(y) * atlas_width + size_t(k) * tex.width) * nc]);
        }
      out.setFrameBuffer(write_buffer(header, tex.channels, band.data(), halves,
                                      int64_t(r) * tex.height, tex.height));
      out.writePixels(tex.height);
    }
  });
}

// Writes the given parts (one header and one pixel pointer each, float32 with
// channels interleaved in texture order) as a single- or multi-part EXR.
void write_parts(const std::string& path, std::vector<Imf::Header>& headers,
                 const std::vector<const float*>& pixels, const std::vector<std::string>& channels) {
  std::vector<half> halves;
  write_or_remove(path, [&] {
    if (headers.size() == 1) {
      Imf::OutputFile out(path.c_str(), headers[0], exr_write_threads(headers[0]));
      out.setFrameBuffer(write_buffer(headers[0], channels, pixels[0], halves));
      out.writePixels(headers[0].dataWindow().max.y + 1);
    } else {
      for (Imf::Header& h : headers) h.setType(Imf::SCANLINEIMAGE);
      Imf::MultiPartOutputFile out(path.c_str(), headers.data(), int(headers.size()),
                                   /*overrideSharedAttributes=*/false,
                                   exr_write_threads(headers[0]));
      for (size_t i = 0; i < headers.size(); ++i) {
        Imf::OutputPart part(out, int(i));
        part.setFrameBuffer(write_buffer(headers[i], exr_part_channels(headers[i].name(), channels),
                                         pixels[i], halves));
        part.writePixels(headers[i].dataWindow().max.y + 1);
      }
    }
  });
}

}  // namespace

ExrCompression exr_compression_from_name(const std::string& name) {
  if (name == "none") return ExrCompression::none;
  if (name == "zip") return ExrCompression::zip;
  if (name == "zips") return ExrCompression::zips;
  if (name == "piz") return ExrCompression::piz;
  throw Error(fmt::format("expected an EXR compression of none, zip, zips or piz, got '{}'", name));
}

int exr_atlas_columns(int depth) {
  int rows = 1;  // the largest divisor of depth not above sqrt(depth)
  for (int r = 2; int64_t(r) * r <= depth; ++r)
    if (depth % r == 0) rows = r;
  return depth / rows;
}

void write_exr(const std::string& path, const Texture& tex, ExrPrecision precision,
               ExrVolumeLayout layout, ExrCompression compression, FiniteCheck finite) {
  check_writable(path, tex, precision, finite);
  std::vector<Imf::Header> specs;
  std::vector<const float*> pixels;
  if (tex.is_volume() && layout == ExrVolumeLayout::atlas) {
    const int columns = exr_atlas_columns(tex.depth);
    const int rows = tex.depth / columns;  // columns * rows == depth: no empty cell
    Imf::Header spec =
        base_header(tex, columns * tex.width, rows * tex.height, precision, "atlas");
    spec.insert(kExrPrefix + "atlas_columns", Imf::IntAttribute(columns));
    spec.insert(kExrPrefix + "atlas_rows", Imf::IntAttribute(rows));
    spec.insert(kExrPrefix + "slice_width", Imf::IntAttribute(tex.width));
    spec.insert(kExrPrefix + "slice_height", Imf::IntAttribute(tex.height));
    spec.insert(kExrPrefix + "slice_count", Imf::IntAttribute(tex.depth));
    spec.compression() = imf_compression(compression);
    write_atlas(path, spec, tex, columns, rows);
    return;
  } else if (tex.is_volume() || tex.is_array()) {
    const bool volume = tex.is_volume();
    const int parts = volume ? tex.depth : tex.layers;
    for (int i = 0; i < parts; ++i) {
      specs.push_back(base_header(tex, tex.width, tex.height, precision,
                                  volume ? "slices" : "layers",
                                  fmt::format("{}{}", volume ? "slice" : "layer", i)));
      pixels.push_back(volume ? tex.texel(0, 0, i, 0) : tex.texel(0, 0, 0, i));
    }
  } else {
    specs.push_back(base_header(tex, tex.width, tex.height, precision, "image"));
    pixels.push_back(tex.data.data());
  }
  for (Imf::Header& header : specs) header.compression() = imf_compression(compression);
  write_parts(path, specs, pixels, tex.channels);
}

}  // namespace skybake

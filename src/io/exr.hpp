// OpenEXR output and input for Textures, through OpenEXR's C++ library: half or float,
// channel names, metadata as header attributes, 3D as one part per slice or
// as a slice atlas with the layout recorded in the header.
//
// File shapes:
//   2D (depth 1, layers 1)  one single-part image, width x height.
//   2D array (layers L)     a multi-part EXR, part i named "layer<i>".
//   volume, atlas           one image of columns x rows slices, slice z at
//                           column z % columns, row z / columns, with
//                           exactly columns x rows = depth cells: rows the
//                           largest divisor of depth not above sqrt(depth)
//                           (32 -> 8 x 4, 7 -> 7 x 1; docs/formats.md "EXR").
//   volume, multipart       a multi-part EXR, part z named "slice<z>".
// Channels keep the texture's names ("R", "G", "B", "A" or any other name);
// in a multi-part file each part's are prefixed with the part's name
// ("layer0.R", "slice3.density"): OpenEXR's layer naming, channel names
// unique across the file, which Blender needs to open it (docs/formats.md
// "Which tools read which file").
// Compression: zip by default (16 lines per block), or zips (1 line), piz or
// none, all lossless; every one gives the same bytes for any thread count.
//
// Header attributes (every part of a multi-part file carries all of them):
//   skybake:<key>          one per Texture::metadata entry, of its type: int,
//                          double, string, v2i, v3i, v2d, v3d.
//   skybake:shape          string "WxHxDxL" (width, height, depth, layers).
//   skybake:channels       string, the channel names in texture order, comma
//                          separated: EXR stores channels sorted by name, so
//                          the file alone loses the order.
//   skybake:layout         string "image", "layers", "atlas" or "slices".
//   skybake:atlas_columns, skybake:atlas_rows, skybake:slice_count,
//   skybake:slice_width, skybake:slice_height
//                          ints, atlas layout only; the reader takes the
//                          atlas from them (checked against skybake:shape).
// No time stamp: OpenEXR writes no DateTime attribute (docs/architecture.md
// "Determinism").
// Metadata keys may therefore not be one of the structural names above
// (shape, channels, layout, atlas_*, slice_*); the writer refuses them.
#pragma once

#include <string>

#include "core/finite_check.hpp"
#include "core/texture.hpp"
#include "io/read_budget.hpp"

namespace skybake {

enum class ExrPrecision { half, float32 };
enum class ExrVolumeLayout { atlas, multipart };
enum class ExrCompression { none, zip, zips, piz };

// "none", "zip", "zips" or "piz"; throws Error otherwise.
ExrCompression exr_compression_from_name(const std::string& name);

// Writes `tex` to exactly `path` (no temporary file: the caller renames).
// Half output rounds to nearest even. Throws IoError (before creating the
// file) when a value is NaN/Inf or, for half, would round to Inf (|v| >=
// 65520); when the texture is empty or both a volume and an array; or when
// OpenEXR fails (the partial file is removed). Throws
// Error when a metadata key is reserved (a programmer error).
// Compression and decompression run on OpenEXR's thread pool, sized to TBB's
// allowed parallelism (--threads).
void write_exr(const std::string& path, const Texture& tex, ExrPrecision precision,
               ExrVolumeLayout layout = ExrVolumeLayout::atlas,
               ExrCompression compression = ExrCompression::zip,
               FiniteCheck finite = FiniteCheck::run);

// Reads an EXR written by write_exr back into a Texture (shape, channel order
// and metadata, with the "skybake:" prefix stripped and the structural
// attributes left out). A foreign EXR reads as a 2D texture (one part) or a
// 2D array (several parts of one size) with the channels in file order (R,
// G, B, A first) and no metadata. Throws IoError when the file cannot be read or its parts do
// not match its skybake:* attributes.
// ExrShape::as_stored ignores skybake:shape and skybake:layout and reads the
// parts as they are, like a foreign EXR (channel order and metadata are still
// taken from the attributes): for a copy whose pixels no longer match what it
// records, e.g. cropped by another tool, which check-tiling still measures.
enum class ExrShape { recorded, as_stored };
// `budget`: the most the decoded float32 pixels may take (io/read_budget.hpp).
Texture read_exr(const std::string& path, ExrShape shape = ExrShape::recorded,
                 uint64_t budget = kNoReadBudget);

// Columns of the slice atlas of a volume with `depth` slices: depth / rows,
// rows the largest divisor of depth not above sqrt(depth).
int exr_atlas_columns(int depth);

// The layout an EXR records (skybake:layout and the atlas ints; "image" or
// "layers" and zeros for a foreign file), for `skybake info`. Throws IoError
// when the file cannot be read.
struct ExrLayout {
  std::string layout;
  int parts = 1;
  int atlas_columns = 0, atlas_rows = 0, slice_count = 0;
};
ExrLayout read_exr_layout(const std::string& path);

}  // namespace skybake

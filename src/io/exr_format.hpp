// What the EXR writer and reader share: the names of skybake's own header
// attributes (exr.hpp, docs/formats.md "EXR") and the size of OpenEXR's
// thread pool.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ImfFrameBuffer.h>
#include <half.h>

namespace skybake {

// The prefix of every attribute skybake writes: "skybake:" + a metadata key,
// or one of the reserved layout keys below.
extern const std::string kExrPrefix;

// Whether `key` (without the prefix) is one of the layout attributes
// (shape, channels, layout, atlas and slice sizes), which no metadata key
// may take.
bool is_reserved_exr_key(const std::string& key);

// The "skybake:channels" attribute's text: the names joined by commas
// (names hold no comma), and back.
std::string join_exr_channels(const std::vector<std::string>& channels);
std::vector<std::string> split_exr_channels(const std::string& text);

// The names a part's channels have in the file: "<part>.<channel>" in a
// part named `part` (OpenEXR's layer naming, "Technical Introduction to
// OpenEXR": a channel name is unique across the parts of a file, and Blender
// and OpenImageIO read each part as the layer of that name), the channels
// themselves when `part` is empty (a single-part file).
std::vector<std::string> exr_part_channels(const std::string& part,
                                           const std::vector<std::string>& channels);

// Interleaved pixels (float, or half for writing half files: OpenEXR
// converts types when reading, not when writing) of `width` texels per row,
// channels in `channels` order, as OpenEXR's frame buffer. `min_x`, `min_y`:
// the data window's origin, the buffer's texel 0.
Imf::FrameBuffer exr_frame_buffer(const std::vector<std::string>& channels, const float* pixels,
                                  int64_t width, int64_t min_x, int64_t min_y);
Imf::FrameBuffer exr_frame_buffer(const std::vector<std::string>& channels, const half* pixels,
                                  int64_t width, int64_t min_x, int64_t min_y);

// OpenEXR's thread pool (compression and decompression of line blocks) as
// large as TBB may be (--threads); returns its size, 0 for the calling
// thread alone. The bytes do not depend on it: blocks are written in order.
int exr_threads();

}  // namespace skybake

// The block-compression plugin: libsquish (Debian libsquish-dev) is the BC1,
// BC3, BC4 and BC5 encoder, and it pulls in libgomp (OpenMP) with it. A
// process that never writes a block-compressed file must not load either
// (`skybake --version`, `validate` and `plan` stay lean), so the one file that
// includes squish.h, squish_plugin.cpp, is built as its own shared library,
// libskybake_bc.so, which encode_bc (block_compression.cpp) opens with dlopen
// the first time it encodes a block.
//
// Where the plugin is looked for, in order: $SKYBAKE_BC_PLUGIN when set (and
// then only there); beside the running executable (the installed layout and
// build/skybake); the build folder the library was compiled for (tests live in
// its subfolders).
//
// The entry point is extern "C" and plain data only: 16 texels of 8-bit RGBA
// in, one block out. Decoding never goes through the plugin: our decoder
// (bc_decoder.cpp) is written from the format specification, independent of
// libsquish.
#pragma once

#include <cstdint>

namespace skybake {

// Bumped whenever the entry point's signature or the meaning of its
// arguments changes.
constexpr int kBcPluginAbi = 1;
constexpr const char* kBcPluginName = "libskybake_bc.so";

// The `format` argument of the entry point (not libsquish's flags, so that
// only the plugin sees squish.h).
enum BcPluginFormat : int { bc_plugin_bc1 = 1, bc_plugin_bc3 = 3, bc_plugin_bc4 = 4, bc_plugin_bc5 = 5 };

}  // namespace skybake

extern "C" {
using SkybakeBcAbiFn = int();
// Compresses one 4x4 block. `rgba` holds 16 texels of R, G, B, A bytes, row by
// row (x fastest); bit i of `mask` says texel i lies inside the image (the
// others are padding the encoder may ignore). BC4 reads R, BC5 R and G, BC1
// R, G, B (always opaque), BC3 all four. Writes 8 bytes (BC1, BC4) or 16
// (BC3, BC5) to `block`. Returns 0, or -1 for an unknown format.
using SkybakeBcCompressFn = int(const uint8_t* rgba, int mask, uint8_t* block, int format);
}

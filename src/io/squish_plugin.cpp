// The entry points of libskybake_bc.so (squish_plugin.hpp): libsquish's
// block encoder behind a plain C interface.
#include "io/squish_plugin.hpp"

#include <squish.h>

namespace {

// Colour fit: libsquish's cluster fit (its default quality) with uniform
// channel weights (metric nullptr), since our channels are data, not
// perceived colour (docs/decisions/dds-files.md).
int squish_flags(int format) {
  switch (format) {
    case skybake::bc_plugin_bc1: return squish::kDxt1 | squish::kColourClusterFit;
    case skybake::bc_plugin_bc3: return squish::kDxt5 | squish::kColourClusterFit;
    case skybake::bc_plugin_bc4: return squish::kBc4;
    case skybake::bc_plugin_bc5: return squish::kBc5;
    default: return 0;
  }
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int skybake_bc_abi() {
  return skybake::kBcPluginAbi;
}

__attribute__((visibility("default"))) int skybake_bc_compress(const uint8_t* rgba, int mask,
                                                               uint8_t* block, int format) {
  const int flags = squish_flags(format);
  if (flags == 0) return -1;
  squish::CompressMasked(rgba, mask, block, flags, nullptr);
  return 0;
}

}  // extern "C"

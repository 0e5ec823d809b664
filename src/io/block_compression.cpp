// The block-compression encoder (block_compression.hpp) and the sizes of the
// formats; libsquish is reached through the plugin (squish_plugin.hpp).
#include "io/block_compression.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "io/plugin_library.hpp"
#include "io/squish_plugin.hpp"

namespace skybake {
namespace {

struct BcInfo {
  const char* name;
  int channels, decoded_channels, block_bytes;
  BcPluginFormat plugin;
};

const BcInfo& info(BcFormat format) {
  static const BcInfo kInfo[] = {
      {"BC1", 3, 4, 8, bc_plugin_bc1},
      {"BC3", 4, 4, 16, bc_plugin_bc3},
      {"BC4", 1, 1, 8, bc_plugin_bc4},
      {"BC5", 2, 2, 16, bc_plugin_bc5},
  };
  return kInfo[int(format)];
}

// ---- the plugin ------------------------------------------------------------

struct BcPlugin {
  SkybakeBcCompressFn* compress = nullptr;
  std::string problem;  // why it could not be loaded, with every path tried
};

BcPlugin load() {
  BcPlugin plugin;
  const PluginLibrary lib = open_plugin_library(
      "SKYBAKE_BC_PLUGIN", kBcPluginName,
      [&](void* handle) {
        auto* abi = reinterpret_cast<SkybakeBcAbiFn*>(::dlsym(handle, "skybake_bc_abi"));
        plugin.compress =
            reinterpret_cast<SkybakeBcCompressFn*>(::dlsym(handle, "skybake_bc_compress"));
        return abi && abi() == kBcPluginAbi && plugin.compress;
      },
      fmt::format("not a skybake block-compression plugin of interface {}", kBcPluginAbi));
  if (!lib.handle)
    plugin.problem = fmt::format(
        "cannot block-compress: the plugin {} (libsquish) could not be loaded; {}",
        kBcPluginName, lib.problem);
  return plugin;
}

SkybakeBcCompressFn* compressor() {
  static const BcPlugin plugin = load();
  if (!plugin.problem.empty()) throw IoError(plugin.problem);
  return plugin.compress;
}

// ---- encoding --------------------------------------------------------------

uint8_t unorm8(float v) {
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// The 16 texels of block (bx, by) as RGBA8, with the mask of those inside the
// slice; padding texels repeat the nearest edge texel (the encoder ignores
// them, but they still have to be defined bytes).
int gather_block(const float* texels, int width, int height, int channels, int bx, int by,
                 uint8_t* rgba) {
  int mask = 0;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const int x = 4 * bx + i, y = 4 * by + j;
      if (x < width && y < height) mask |= 1 << (4 * j + i);
      const float* src =
          texels + (size_t(std::min(y, height - 1)) * width + size_t(std::min(x, width - 1))) *
                       channels;
      uint8_t* dst = rgba + 4 * (4 * j + i);
      dst[0] = dst[1] = dst[2] = 0;
      dst[3] = 255;  // a missing alpha is opaque
      for (int c = 0; c < channels; ++c) dst[c] = unorm8(src[c]);
    }
  }
  return mask;
}

}  // namespace

const char* bc_format_name(BcFormat format) {
  return info(format).name;
}
int bc_channel_count(BcFormat format) {
  return info(format).channels;
}
int bc_decoded_channel_count(BcFormat format) {
  return info(format).decoded_channels;
}
int bc_block_bytes(BcFormat format) {
  return info(format).block_bytes;
}

size_t bc_row_pitch(int width, BcFormat format) {
  return size_t(std::max(1, (width + 3) / 4)) * size_t(bc_block_bytes(format));
}

size_t bc_slice_bytes(int width, int height, BcFormat format) {
  return bc_row_pitch(width, format) * size_t(std::max(1, (height + 3) / 4));
}

std::vector<uint8_t> encode_bc(const float* texels, int width, int height, int channels,
                               BcFormat format) {
  const BcInfo& f = info(format);
  if (width < 1 || height < 1 || channels < 1 || channels > f.channels)
    throw Error(fmt::format("encode_bc: expected a non-empty slice of 1 to {} channels for {}, "
                            "got {}x{} with {} channels",
                            f.channels, f.name, width, height, channels));
  SkybakeBcCompressFn* compress = compressor();
  const int blocks_x = (width + 3) / 4, blocks_y = (height + 3) / 4;
  std::vector<uint8_t> out(bc_slice_bytes(width, height, format));
  tbb::parallel_for(0, blocks_y, [&](int by) {
    uint8_t rgba[64];
    for (int bx = 0; bx < blocks_x; ++bx) {
      const int mask = gather_block(texels, width, height, channels, bx, by, rgba);
      uint8_t* block = out.data() + (size_t(by) * blocks_x + bx) * size_t(f.block_bytes);
      compress(rgba, mask, block, f.plugin);
    }
  });
  return out;
}

bool BcSliceCache::Key::operator<(const Key& o) const {
  return std::tie(texels, width, height, channels, format) <
         std::tie(o.texels, o.width, o.height, o.channels, o.format);
}

const std::vector<uint8_t>& BcSliceCache::encode(const float* texels, int width, int height,
                                                 int channels, BcFormat format) {
  const Key key{texels, width, height, channels, format};
  auto it = slices_.find(key);
  if (it == slices_.end())
    it = slices_.emplace(key, encode_bc(texels, width, height, channels, format)).first;
  return it->second;
}

const std::vector<uint8_t>& encode_bc_slice(BcSliceCache* cache, std::vector<uint8_t>& scratch,
                                            const float* texels, int width, int height,
                                            int channels, BcFormat format) {
  if (cache) return cache->encode(texels, width, height, channels, format);
  scratch = encode_bc(texels, width, height, channels, format);
  return scratch;
}

}  // namespace skybake

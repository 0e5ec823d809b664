// The block-compression encoder (block_compression.hpp) and the sizes of the
// formats; libsquish is reached through the plugin (squish_plugin.hpp).
#include "io/block_compression.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
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

std::string executable_dir() {
  char buffer[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return "";
  const std::string exe(buffer, size_t(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? "" : exe.substr(0, slash);
}

std::vector<std::string> candidates() {
  if (const char* env = std::getenv("SKYBAKE_BC_PLUGIN"); env && *env) return {env};
  std::vector<std::string> paths;
  if (const std::string dir = executable_dir(); !dir.empty())
    paths.push_back(dir + "/" + kBcPluginName);
#ifdef SKYBAKE_PLUGIN_BUILD_DIR
  const std::string built = std::string(SKYBAKE_PLUGIN_BUILD_DIR) + "/" + kBcPluginName;
  if (paths.empty() || paths.front() != built) paths.push_back(built);
#endif
  return paths;
}

BcPlugin load() {
  BcPlugin plugin;
  std::vector<std::string> tried;
  for (const std::string& path : candidates()) {
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      tried.push_back(fmt::format("{} ({})", path, why ? why : "cannot open"));
      continue;
    }
    auto* abi = reinterpret_cast<SkybakeBcAbiFn*>(::dlsym(handle, "skybake_bc_abi"));
    plugin.compress = reinterpret_cast<SkybakeBcCompressFn*>(::dlsym(handle, "skybake_bc_compress"));
    if (abi && abi() == kBcPluginAbi && plugin.compress) return plugin;
    tried.push_back(fmt::format("{} (not a skybake block-compression plugin of interface {})",
                                path, kBcPluginAbi));
    plugin.compress = nullptr;
    ::dlclose(handle);
  }
  std::string list;
  for (const std::string& t : tried) list += (list.empty() ? "" : "; ") + t;
  plugin.problem = fmt::format(
      "cannot block-compress: the plugin {} (libsquish) could not be loaded; tried {}",
      kBcPluginName, list.empty() ? std::string("no path") : list);
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

}  // namespace skybake

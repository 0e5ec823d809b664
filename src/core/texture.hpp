// The one texture container every product bakes into and every writer reads.
//
// Shape: width x height x depth texels, `layers` array layers (a 2D array has
// depth == 1 and layers > 1; a volume has depth > 1 and layers == 1), with
// named channels stored as float32. Layout, channel fastest:
//   index = (((layer * depth + z) * height + y) * width + x) * channels + c
// so x is the fastest spatial axis (the layout DDS, EXR and our VDB export use).
// Metadata is an ordered map of typed values (core/metadata.hpp) that writers
// copy into file headers and the manifest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/fresh_pages.hpp"
#include "core/metadata.hpp"

namespace skybake {

// A texture's floats, from fresh_pages' allocator: zeroed, and from 1 MB up
// in huge pages faulted in on every thread (core/fresh_pages.hpp).
using TexelVector = std::vector<float, FreshPagesAllocator<float>>;

struct Texture {
  int width = 0;
  int height = 0;
  int depth = 1;   // > 1 for volumes
  int layers = 1;  // > 1 for 2D arrays
  std::vector<std::string> channels;
  TexelVector data;
  Metadata metadata;

  Texture() = default;
  Texture(int width, int height, int depth, int layers, std::vector<std::string> channels);

  int channel_count() const { return static_cast<int>(channels.size()); }
  bool is_volume() const { return depth > 1; }
  bool is_array() const { return layers > 1; }
  size_t texel_count() const {
    return size_t(width) * size_t(height) * size_t(depth) * size_t(layers);
  }
  size_t index(int x, int y, int z = 0, int layer = 0) const {
    return ((((size_t(layer) * depth + z) * height + y) * width + x)) * channels.size();
  }
  float& at(int x, int y, int z, int layer, int c) { return data[index(x, y, z, layer) + c]; }
  float at(int x, int y, int z, int layer, int c) const { return data[index(x, y, z, layer) + c]; }
  float* texel(int x, int y, int z = 0, int layer = 0) { return &data[index(x, y, z, layer)]; }
  const float* texel(int x, int y, int z = 0, int layer = 0) const {
    return &data[index(x, y, z, layer)];
  }
  // Index of a channel by name, or -1.
  int channel_index(const std::string& name) const;
  // "256x64", "128x128x128", "192x108[8]"
  std::string shape_string() const;
};

// Throws IoError naming `what` and the first offending texel when any value
// is NaN or infinite. Every writer calls this before it opens a file, unless
// its caller already has (core/finite_check.hpp).
void check_finite(const Texture& tex, const std::string& what);

// Whether every value is finite (no NaN, no infinity): check_finite's scan,
// for callers that only need to know.
bool texture_is_finite(const Texture& tex);

}  // namespace skybake

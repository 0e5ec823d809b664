#include "core/texture.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/fresh_pages.hpp"

namespace skybake {

Texture::Texture(int w, int h, int d, int l, std::vector<std::string> ch)
    : width(w), height(h), depth(d), layers(l), channels(std::move(ch)) {
  const size_t n = texel_count() * channels.size();
  // A large texture's pages are faulted in by every thread before the
  // zeroing, which is then a plain memset (core/fresh_pages.hpp).
  if (n * sizeof(float) >= kPopulateMinBytes) {
    data.reserve(n);
    populate_pages(data.data(), n * sizeof(float));
  }
  data.assign(n, 0.0f);
}

int Texture::channel_index(const std::string& name) const {
  for (size_t i = 0; i < channels.size(); ++i)
    if (channels[i] == name) return static_cast<int>(i);
  return -1;
}

std::string Texture::shape_string() const {
  std::string s = fmt::format("{}x{}", width, height);
  if (depth > 1) s += fmt::format("x{}", depth);
  if (layers > 1) s += fmt::format("[{}]", layers);
  return s;
}

void check_finite(const Texture& tex, const std::string& what) {
  const size_t nc = tex.channels.size();
  for (size_t i = 0; i < tex.data.size(); ++i) {
    if (std::isfinite(tex.data[i])) continue;
    size_t t = i / nc;
    const int c = int(i % nc);
    const int x = int(t % tex.width);
    t /= tex.width;
    const int y = int(t % tex.height);
    t /= tex.height;
    const int z = int(t % tex.depth);
    const int layer = int(t / tex.depth);
    throw IoError(fmt::format(
        "{}: refusing to write a non-finite value ({}) at texel x={} y={} z={} layer={} "
        "channel {}",
        what, tex.data[i], x, y, z, layer, tex.channels[c]));
  }
}

}  // namespace skybake

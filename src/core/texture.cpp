#include "core/texture.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

Texture::Texture(int w, int h, int d, int l, std::vector<std::string> ch)
    : width(w), height(h), depth(d), layers(l), channels(std::move(ch)) {
  // Zeros from TexelVector's allocator: the kernel's fill of fresh pages,
  // on every thread, for a large texture (core/fresh_pages.hpp).
  data.resize(texel_count() * channels.size());
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

namespace {

// Whether any of v[0 .. n) is NaN or infinite: all exponent bits set. A
// branch-free OR over the values, which the compiler vectorizes; every
// writer calls check_finite on every texel (four times over a volume
// written in four formats), so the scan runs at memory speed and the
// texel is looked for only when there is one.
bool any_non_finite(const float* v, size_t n) {
  constexpr uint32_t kExponent = 0x7f800000u;
  uint32_t bad = 0;
  for (size_t i = 0; i < n; ++i) {
    uint32_t bits;
    std::memcpy(&bits, v + i, sizeof bits);
    bad |= uint32_t((bits & kExponent) == kExponent);
  }
  return bad != 0;
}

}  // namespace

bool texture_is_finite(const Texture& tex) {
  return !any_non_finite(tex.data.data(), tex.data.size());
}

void check_finite(const Texture& tex, const std::string& what) {
  if (texture_is_finite(tex)) return;
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

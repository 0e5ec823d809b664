// The "skybake:shape" attribute of the EXR and VDB files skybake writes:
// "WxHxDxL", the texture's width, height, depth and layers. Header only: the
// VDB plugin (a separate library) reads it too.
#pragma once

#include <cerrno>
#include <cstdlib>
#include <optional>
#include <string>

namespace skybake {

struct ShapeText {
  int width = 0, height = 0, depth = 1, layers = 1;
};

// The four integers of "WxHxDxL", each from 1 to `max` (at most INT_MAX),
// or nullopt for any other text (signs, spaces, missing or extra parts).
inline std::optional<ShapeText> parse_shape_text(const std::string& text, long long max) {
  int values[4];
  const char* p = text.c_str();
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && *p++ != 'x') return std::nullopt;
    if (*p < '0' || *p > '9') return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(p, &end, 10);
    if (errno != 0 || v < 1 || v > max) return std::nullopt;
    values[i] = int(v);
    p = end;
  }
  if (*p != '\0') return std::nullopt;
  return ShapeText{values[0], values[1], values[2], values[3]};
}

}  // namespace skybake

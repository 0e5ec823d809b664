#include "noise/perlin_worley.hpp"

namespace skybake {

const char* remap_name(PerlinWorleyRemap remap) {
  switch (remap) {
    case PerlinWorleyRemap::worley_new_min:
      return "worley_new_min";
    case PerlinWorleyRemap::worley_old_min:
      return "worley_old_min";
    case PerlinWorleyRemap::dilate:
      return "dilate";
  }
  return "?";
}

std::optional<PerlinWorleyRemap> remap_from_name(const std::string& name) {
  for (PerlinWorleyRemap r : {PerlinWorleyRemap::worley_new_min, PerlinWorleyRemap::worley_old_min,
                              PerlinWorleyRemap::dilate})
    if (name == remap_name(r)) return r;
  return std::nullopt;
}

}  // namespace skybake

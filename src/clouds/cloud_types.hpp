// The cloud-type texture (Hillaire 2016 "Physically Based Sky, Atmosphere and
// Cloud Rendering in Frostbite", sec. 5.3.1, figure 31): x = cloud type,
// y = normalized height in the cloud layer.
//
//   R  density profile of the type at that height (height_profile.hpp:
//      smoothstep(a, b, h) - smoothstep(c, d, h), ramps from the preset)
//   G  erosion amount: 0 smooth, 1 fully eroded by the detail noise
//
// Shape: (types x type_width) wide, `height` rows, 2 channels, values in
// [0, 1]. Columns: type i occupies columns [i * type_width, (i + 1) *
// type_width), all identical; the order is the spec's (stratus,
// stratocumulus, cumulus, cumulonimbus, then the preset's extra types).
// A shader samples it at u = type_u_from_index(index, types) = (index + 0.5) /
// types, the centre of the type's band, so bilinear filtering returns the
// type exactly and blends neighbouring types between centres. The weather
// map's Frostbite layout stores exactly this u in G (weather_map.hpp).
// Rows: row 0 is the BOTTOM of the layer, row j holds h = (j + 0.5) / height
// (texel centres), so v = h; previews therefore show the layer upside down.
// Threading: none needed (a few thousand texels); pure function.
#pragma once

#include <vector>

#include "clouds/height_profile.hpp"
#include "core/texture.hpp"

namespace skybake {

struct CloudTypesSpec {
  int height = 128;                                             // rows (normalized heights), >= 1
  int type_width = 1;                                           // texel columns per type, >= 1
  std::vector<CloudTypeProfile> types = default_cloud_types();  // x order
};

std::vector<SpecProblem> spec_problems(const CloudTypesSpec& spec);

// Texture u of the centre of type `index` (may be fractional: a blend) among
// `types`, and its inverse.
inline double type_u_from_index(double index, int types) {
  return (index + 0.5) / types;
}
inline double index_from_type_u(double u, int types) {
  return u * types - 0.5;
}

// Channels "R" (density), "G" (erosion); metadata: product, type names and
// ramps per column band, the u and v mappings.
// Throws Error when spec_problems() is not empty.
Texture bake_cloud_types(const CloudTypesSpec& spec);

}  // namespace skybake

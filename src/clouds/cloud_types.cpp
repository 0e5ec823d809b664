#include "clouds/cloud_types.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

std::vector<SpecProblem> spec_problems(const CloudTypesSpec& spec) {
  std::vector<SpecProblem> out;
  if (spec.height < 1 || spec.height > 4096)
    out.push_back({"size", fmt::format("expected 1 .. 4096 rows, got {}", spec.height)});
  if (spec.type_width < 1 || spec.type_width > 64)
    out.push_back({"type_width", fmt::format("expected 1 .. 64, got {}", spec.type_width)});
  if (spec.types.empty()) out.push_back({"types", "expected at least one cloud type, got none"});
  for (const SpecProblem& p : cloud_type_problems(spec.types)) out.push_back(p);
  return out;
}

Texture bake_cloud_types(const CloudTypesSpec& spec) {
  const auto problems = spec_problems(spec);
  if (!problems.empty())
    throw Error(fmt::format("cloud_types: {}: {}", problems[0].field, problems[0].message));
  const int types = int(spec.types.size());
  Texture tex(types * spec.type_width, spec.height, 1, 1, {"R", "G"});
  for (int i = 0; i < types; ++i) {
    const CloudTypeProfile& type = spec.types[i];
    for (int j = 0; j < spec.height; ++j) {
      const double h = height_from_row(j, spec.height);
      const float density = float(compute_height_density(type.density, h));
      const float erosion = float(compute_height_erosion(type, h));
      for (int k = 0; k < spec.type_width; ++k) {
        float* t = tex.texel(i * spec.type_width + k, j);
        t[0] = density;
        t[1] = erosion;
      }
    }
  }
  Metadata& m = tex.metadata;
  set_meta(m, "product", "cloud_types");
  set_meta(m, "channel.R",
           "density over normalized height: smoothstep(a, b, h) - smoothstep(c, d, h)");
  set_meta(m, "channel.G",
           "erosion amount (0 smooth, 1 fully eroded), linear from base (h = a) to top (h = d)");
  set_meta(m, "type_count", types);
  set_meta(m, "type_width", spec.type_width);
  set_meta(m, "u", "u = (type_index + 0.5) / type_count (centre of the type's column band)");
  set_meta(m, "v", "v = h, row 0 = bottom of the layer, row j holds h = (j + 0.5) / rows");
  for (int i = 0; i < types; ++i) {
    const CloudTypeProfile& t = spec.types[i];
    set_meta(m, fmt::format("type.{}", i), t.name);
    // density = smoothstep(rise.x, rise.y, h) - smoothstep(fall.x, fall.y, h)
    set_meta(m, fmt::format("type.{}.density_rise", i), glm::dvec2(t.density.a, t.density.b));
    set_meta(m, fmt::format("type.{}.density_fall", i), glm::dvec2(t.density.c, t.density.d));
    set_meta(m, fmt::format("type.{}.erosion", i), glm::dvec2(t.erosion_base, t.erosion_top));
  }
  return tex;
}

}  // namespace skybake

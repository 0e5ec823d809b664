#include "atmosphere/table_convention.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

const char* table_convention_name(TableConvention c) {
  return c == TableConvention::hillaire_demo ? "hillaire_demo" : "skybake";
}

std::optional<TableConvention> find_table_convention(const std::string& name) {
  for (TableConvention c : {TableConvention::skybake, TableConvention::hillaire_demo})
    if (name == table_convention_name(c)) return c;
  return std::nullopt;
}

TableConvention table_convention_from_name(const std::string& name) {
  if (const auto c = find_table_convention(name)) return *c;
  throw Error(fmt::format("unknown table convention '{}' (expected skybake or hillaire_demo)",
                          name));
}

TableConvention table_convention_of(const Texture& lut) {
  if (!lut.metadata.count("convention")) return TableConvention::skybake;
  return table_convention_from_name(meta_string(lut.metadata, "convention"));
}

double unit_of_texel(TexelPlacement p, int i, int n) {
  switch (p) {
    case TexelPlacement::ends: return double(i) / double(n - 1);
    case TexelPlacement::centres: return texel_center(i, n);
    case TexelPlacement::sub_uv: return (texel_center(i, n) * (n + 1) - 0.5) / n;
  }
  return 0.0;
}

double texture_coord_of_unit(TexelPlacement p, double x, int n) {
  switch (p) {
    case TexelPlacement::ends: return texel_coord_from_unit(x, n);
    case TexelPlacement::centres: return x;
    case TexelPlacement::sub_uv: return (x * n + 0.5) / (n + 1);
  }
  return 0.0;
}

double skybake_coord_of_texel(TexelPlacement p, int i, int n) {
  if (p == TexelPlacement::ends) return texel_center(i, n);
  return texel_coord_from_unit(unit_of_texel(p, i, n), n);
}

double demo_skyview_unit_from_cos_azimuth(double cos_phi) {
  return std::sqrt(std::clamp(0.5 - 0.5 * cos_phi, 0.0, 1.0));
}

double demo_skyview_cos_azimuth_from_unit(double x) { return clamp_cosine(1.0 - 2.0 * x * x); }

double demo_aerial_slice_distance(int k, int n, double range_m) {
  const double s = texel_center(k, n);
  return s * s * range_m;
}

double demo_aerial_w_from_distance(double d, double range_m) {
  return std::sqrt(std::max(d, 0.0) / range_m);
}

}  // namespace skybake

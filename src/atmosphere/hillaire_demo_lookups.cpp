#include "atmosphere/hillaire_demo_lookups.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/table_convention.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

namespace {

// A texture coordinate of skybake's layout moved to placement p.
double placed(TexelPlacement p, double skybake_coord, int n) {
  const double x = std::clamp(unit_from_texel_coord(skybake_coord, n), 0.0, 1.0);
  return texture_coord_of_unit(p, x, n);
}

}  // namespace

glm::dvec3 lookup_demo_transmittance_to_top(const Texture& lut, const Atmosphere& atm, double r,
                                            double mu) {
  const glm::dvec2 uv = transmittance_uv_from_r_mu(atm, r, mu, lut.width, lut.height);
  const TexelPlacement p = TexelPlacement::centres;
  return glm::dvec3(sample_bilinear(lut, placed(p, uv.x, lut.width), placed(p, uv.y, lut.height),
                                    0, 0, false));
}

glm::dvec3 lookup_demo_multiscattering(const Texture& lut, const Atmosphere& atm, double r,
                                       double mu_s) {
  const glm::dvec2 uv = multiscattering_uv_from_r_mu_s(atm, r, mu_s, lut.width, lut.height);
  const TexelPlacement p = TexelPlacement::sub_uv;
  return glm::dvec3(sample_bilinear(lut, placed(p, uv.x, lut.width), placed(p, uv.y, lut.height),
                                    0, 0, false));
}

glm::dvec3 lookup_demo_skyview(const Texture& lut, int layer, const Atmosphere& atm, double r,
                               SkyviewDirection view) {
  const glm::dvec2 uv = skyview_uv_from_view(atm, r, view, lut.width, lut.height);
  const TexelPlacement p = TexelPlacement::sub_uv;
  const double x_u = demo_skyview_unit_from_cos_azimuth(std::cos(view.azimuth_rad));
  return glm::dvec3(sample_bilinear(lut, texture_coord_of_unit(p, x_u, lut.width),
                                    placed(p, uv.y, lut.height), 0, layer, false));
}

glm::dvec4 lookup_demo_aerial_perspective(const Texture& lut, double depth_range_m,
                                          glm::dvec2 screen_uv, double distance_m) {
  const int n = lut.depth;
  const double d = std::max(distance_m, 0.0);
  const double s = demo_aerial_w_from_distance(d, depth_range_m) * n - 0.5;  // slice coordinate
  if (s < 0.0) {
    const double d0 = demo_aerial_slice_distance(0, n, depth_range_m);
    const glm::dvec4 first = sample_bilinear(lut, screen_uv.x, screen_uv.y, 0, 0, false);
    return first * std::clamp(d / d0, 0.0, 1.0);
  }
  return sample_aerial_slices(lut, screen_uv, s);
}

}  // namespace skybake

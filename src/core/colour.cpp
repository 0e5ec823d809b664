#include "core/colour.hpp"

namespace skybake {

Chromaticities chromaticities_of(ColourSpace space) {
  if (space == ColourSpace::acescg)
    return {{0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044}, {0.32168, 0.33767}};
  return {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
}

std::string colour_space_name(ColourSpace space) {
  return space == ColourSpace::acescg ? "acescg" : "rec709";
}

namespace {

// XYZ of chromaticity (x, y) at Y = 1.
glm::dvec3 colour_xyz_of_xy(const glm::dvec2& xy) {
  return {xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y};
}

}  // namespace

glm::dmat3 xyz_from_rgb(const Chromaticities& c) {
  // glm matrices are column-major: column k is primary k's XYZ.
  const glm::dmat3 primaries(colour_xyz_of_xy(c.red), colour_xyz_of_xy(c.green),
                             colour_xyz_of_xy(c.blue));
  const glm::dvec3 scale = glm::inverse(primaries) * colour_xyz_of_xy(c.white);
  return glm::dmat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
}

glm::dmat3 rgb_from_xyz(const Chromaticities& c) { return glm::inverse(xyz_from_rgb(c)); }

glm::dvec2 uv_prime_from_xyz(const glm::dvec3& xyz) {
  const double d = xyz.x + 15.0 * xyz.y + 3.0 * xyz.z;
  if (!(d > 0.0)) return glm::dvec2(0.0);
  return {4.0 * xyz.x / d, 9.0 * xyz.y / d};
}

glm::dvec3 xyz_from_uv_prime(const glm::dvec2& uv, double luminance) {
  return {luminance * 9.0 * uv.x / (4.0 * uv.y), luminance,
          luminance * (12.0 - 3.0 * uv.x - 20.0 * uv.y) / (4.0 * uv.y)};
}

glm::dvec2 xy_from_xyz(const glm::dvec3& xyz) {
  const double s = xyz.x + xyz.y + xyz.z;
  if (!(s > 0.0)) return glm::dvec2(0.0);
  return {xyz.x / s, xyz.y / s};
}

}  // namespace skybake

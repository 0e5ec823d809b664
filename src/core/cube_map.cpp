#include "core/cube_map.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

glm::dvec3 cube_direction(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  glm::dvec3 d(0.0);
  switch (face) {  // the inverse of cube_coord's table
    case 0: d = {1.0, -tc, -sc}; break;
    case 1: d = {-1.0, -tc, sc}; break;
    case 2: d = {sc, 1.0, tc}; break;
    case 3: d = {sc, -1.0, -tc}; break;
    case 4: d = {sc, -tc, 1.0}; break;
    default: d = {-sc, -tc, -1.0}; break;
  }
  return glm::normalize(d);
}

glm::dvec3 cube_texel_direction(int face, int i, int j, int n) {
  return cube_direction(face, (i + 0.5) / n, (j + 0.5) / n);
}

CubeCoord cube_coord(glm::dvec3 d) {
  const glm::dvec3 a = glm::abs(d);
  double sc = 0.0, tc = 0.0, ma = 1.0;
  CubeCoord c;
  if (a.x >= a.y && a.x >= a.z) {
    c.face = d.x >= 0.0 ? 0 : 1;
    sc = d.x >= 0.0 ? -d.z : d.z, tc = -d.y, ma = a.x;
  } else if (a.y >= a.z) {
    c.face = d.y >= 0.0 ? 2 : 3;
    sc = d.x, tc = d.y >= 0.0 ? d.z : -d.z, ma = a.y;
  } else {
    c.face = d.z >= 0.0 ? 4 : 5;
    sc = d.z >= 0.0 ? d.x : -d.x, tc = -d.y, ma = a.z;
  }
  c.s = 0.5 * (sc / ma + 1.0);
  c.t = 0.5 * (tc / ma + 1.0);
  return c;
}

CubeTexel cube_texel_mirrored_z(int face, int i, int j, int n) {
  switch (face) {
    case 0:
    case 1: return {face, n - 1 - i, j};
    case 2:
    case 3: return {face, i, n - 1 - j};
    case 4: return {5, n - 1 - i, j};
    default: return {4, n - 1 - i, j};
  }
}

bool cube_texel_in_z_half(int face, int i, int j, int n) {
  // The first of each mirror pair: +Z of the +Z / -Z pairs, the lower
  // column (+X, -X) or row (+Y, -Y) within a face, a texel on the mirror.
  const CubeTexel m = cube_texel_mirrored_z(face, i, j, n);
  return m.face != face ? face < m.face : i + j <= m.i + m.j;
}

void fill_z_mirrors(Texture& tex) {
  const int n = tex.width, channels = tex.channel_count();
  for (int layer = 0; layer < tex.layers; ++layer) {
    const int cube = layer / kCubeFaces, face = layer % kCubeFaces;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (cube_texel_in_z_half(face, i, j, n)) continue;
        const CubeTexel m = cube_texel_mirrored_z(face, i, j, n);
        std::copy_n(tex.texel(m.i, m.j, 0, kCubeFaces * cube + m.face), channels,
                    tex.texel(i, j, 0, layer));
      }
  }
}

namespace {

// The solid angle of the cube-face rectangle [0, x] x [0, y] at distance 1
// (the integral of 1 / (1 + x^2 + y^2)^(3/2)).
double cube_corner_area(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

}  // namespace

double cube_texel_solid_angle(int i, int j, int n) {
  const double x0 = 2.0 * i / n - 1.0, x1 = 2.0 * (i + 1) / n - 1.0;
  const double y0 = 2.0 * j / n - 1.0, y1 = 2.0 * (j + 1) / n - 1.0;
  return cube_corner_area(x1, y1) - cube_corner_area(x0, y1) - cube_corner_area(x1, y0) +
         cube_corner_area(x0, y0);
}

glm::dvec3 sample_cube(const Texture& level, int cube, glm::dvec3 d) {
  return sample_cube(level, cube, cube_coord(d));
}

glm::dvec3 sample_cube(const Texture& level, int cube, const CubeCoord& c) {
  const int n = level.width, layer = kCubeFaces * cube + c.face;
  const double fx = std::clamp(c.s * n - 0.5, 0.0, n - 1.0);
  const double fy = std::clamp(c.t * n - 0.5, 0.0, n - 1.0);
  const int x0 = std::min(int(fx), std::max(n - 2, 0)), y0 = std::min(int(fy), std::max(n - 2, 0));
  const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
  const double ax = fx - x0, ay = fy - y0;
  const float *p00 = level.texel(x0, y0, 0, layer), *p10 = level.texel(x1, y0, 0, layer);
  const float *p01 = level.texel(x0, y1, 0, layer), *p11 = level.texel(x1, y1, 0, layer);
  glm::dvec3 v(0.0);
  for (int ch = 0; ch < 3; ++ch) {
    const double a = p00[ch] * (1 - ax) + p10[ch] * ax;
    const double b = p01[ch] * (1 - ax) + p11[ch] * ax;
    v[ch] = a * (1 - ay) + b * ay;
  }
  return v;
}

}  // namespace skybake

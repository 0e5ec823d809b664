// Tests for core/cube_map.hpp against the face table of the OpenGL 4.6
// specification (sec. 8.13, table 8.19), written out here case by case, and
// the exact solid angles against the sphere's 4 pi.
#include "core/cube_map.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/math.hpp"

namespace skybake {
namespace {

void expect_direction(glm::dvec3 got, glm::dvec3 want) {
  want = glm::normalize(want);
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
  EXPECT_NEAR(got.z, want.z, 1e-12);
}

TEST(CubeMap, FaceCentresAreTheAxes) {
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) expect_direction(cube_direction(f, 0.5, 0.5), axes[f]);
}

// (s, t) = (0, 0), the first texel's corner, per the table: sc = -1, tc = -1.
TEST(CubeMap, FirstCornerOfEachFaceFollowsTheTable) {
  expect_direction(cube_direction(0, 0, 0), {1, 1, 1});     // +X: sc = -rz, tc = -ry
  expect_direction(cube_direction(1, 0, 0), {-1, 1, -1});   // -X: sc = +rz, tc = -ry
  expect_direction(cube_direction(2, 0, 0), {-1, 1, -1});   // +Y: sc = +rx, tc = +rz
  expect_direction(cube_direction(3, 0, 0), {-1, -1, 1});   // -Y: sc = +rx, tc = -rz
  expect_direction(cube_direction(4, 0, 0), {-1, 1, 1});    // +Z: sc = +rx, tc = -ry
  expect_direction(cube_direction(5, 0, 0), {1, 1, -1});    // -Z: sc = -rx, tc = -ry
}

TEST(CubeMap, CoordinatesInvertDirections) {
  for (int f = 0; f < 6; ++f)
    for (double s : {0.1, 0.5, 0.93})
      for (double t : {0.02, 0.4, 0.77}) {
        const CubeCoord c = cube_coord(cube_direction(f, s, t) * 3.0);
        EXPECT_EQ(c.face, f);
        EXPECT_NEAR(c.s, s, 1e-12);
        EXPECT_NEAR(c.t, t, 1e-12);
      }
}

TEST(CubeMap, TexelSolidAnglesCoverTheSphere) {
  for (int n : {1, 3, 16}) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) sum += cube_texel_solid_angle(i, j, n);
    EXPECT_NEAR(6.0 * sum, 4.0 * kPi, 1e-12) << n;
  }
  // A corner texel is smaller than a centre one (it sees the sphere slanted).
  EXPECT_LT(cube_texel_solid_angle(0, 0, 16), cube_texel_solid_angle(8, 8, 16));
}

TEST(CubeMap, ZMirrorTexelsMirrorTheirDirections) {
  for (int n : {1, 4, 5}) {
    int kept = 0, self = 0;
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const CubeTexel m = cube_texel_mirrored_z(f, i, j, n);
          const glm::dvec3 d = cube_texel_direction(f, i, j, n);
          expect_direction(cube_texel_direction(m.face, m.i, m.j, n), {d.x, d.y, -d.z});
          const CubeTexel back = cube_texel_mirrored_z(m.face, m.i, m.j, n);
          EXPECT_TRUE(back.face == f && back.i == i && back.j == j);
          const bool same = m.face == f && m.i == i && m.j == j;
          const bool in = cube_texel_in_z_half(f, i, j, n);
          // The half and its mirror tile the cube: exactly one of a pair
          // is in it, a texel that mirrors itself is.
          EXPECT_EQ(in, same || !cube_texel_in_z_half(m.face, m.i, m.j, n)) << f << i << j;
          kept += in;
          self += same;
        }
    EXPECT_EQ(2 * kept - self, 6 * n * n) << n;
  }
}

TEST(CubeMap, FillZMirrorsCopiesEachTexelFromItsMirror) {
  const int n = 6;
  Texture t(n, n, 1, 12, {"R", "G"});  // two cubes
  for (size_t k = 0; k < t.data.size(); ++k) t.data[k] = float(k);
  const Texture before = t;
  fill_z_mirrors(t);
  for (int layer = 0; layer < 12; ++layer)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int f = layer % 6;
        const CubeTexel m = cube_texel_mirrored_z(f, i, j, n);
        const int from = cube_texel_in_z_half(f, i, j, n) ? layer : 6 * (layer / 6) + m.face;
        const int fi = cube_texel_in_z_half(f, i, j, n) ? i : m.i;
        const int fj = cube_texel_in_z_half(f, i, j, n) ? j : m.j;
        for (int c = 0; c < 2; ++c) EXPECT_EQ(t.at(i, j, 0, layer, c), before.at(fi, fj, 0, from, c));
      }
}

TEST(CubeMap, SampleReadsALinearFieldExactlyInsideAFace) {
  const int n = 8;
  Texture t(n, n, 1, 6, {"R", "G", "B"});
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        t.at(i, j, 0, f, 0) = float(i);
        t.at(i, j, 0, f, 1) = float(j);
        t.at(i, j, 0, f, 2) = float(f);
      }
  const glm::dvec3 v = sample_cube(t, 0, cube_direction(4, 0.4, 0.6));
  EXPECT_NEAR(v.x, 0.4 * n - 0.5, 1e-6);
  EXPECT_NEAR(v.y, 0.6 * n - 0.5, 1e-6);
  EXPECT_EQ(v.z, 4.0);
}

}  // namespace
}  // namespace skybake

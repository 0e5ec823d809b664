// Cube-map geometry and reads: the face order and texel directions of
// Direct3D, Vulkan and OpenGL (OpenGL 4.6 spec. sec. 8.13 "Cube Map Texture
// Selection", table 8.19; KTX 2.0 and DDS store faces in this order).
//
// Faces f = 0..5: +X, -X, +Y, -Y, +Z, -Z. The face of a direction is its
// major axis; within it (s, t) in [0, 1] are ((sc / |ma|) + 1) / 2 and
// ((tc / |ma|) + 1) / 2 with (sc, tc, ma) per face:
//   +X: (-z, -y, x)  -X: (z, -y, x)  +Y: (x, z, y)
//   -Y: (x, -z, y)   +Z: (x, -y, z)  -Z: (-x, -y, z)
// and texel (i, j) of an n x n face (row j from the top of the stored face)
// has its centre at s = (i + 0.5) / n, t = (j + 0.5) / n.
//
// A cube texture is a Texture of square faces with layers = 6 per cube
// (layer 6 c + f), as write_dds_cube and write_ktx2_cube store them.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/texture.hpp"

namespace skybake {

constexpr int kCubeFaces = 6;

// The unit direction through (s, t) of face `face`.
glm::dvec3 cube_direction(int face, double s, double t);
// The unit direction through the centre of texel (i, j) of an n x n face.
glm::dvec3 cube_texel_direction(int face, int i, int j, int n);

// The face a direction selects and its (s, t), by the table above.
struct CubeCoord {
  int face = 0;
  double s = 0.5, t = 0.5;
};
CubeCoord cube_coord(glm::dvec3 d);

// The texel mirroring (face, i, j) of an n x n face through the plane
// z = 0 (x and y kept), by the table above: +X and -X reverse their
// columns, +Y and -Y their rows, +Z and -Z swap with their columns
// reversed.
struct CubeTexel {
  int face = 0, i = 0, j = 0;
};
CubeTexel cube_texel_mirrored_z(int face, int i, int j, int n);
// The half a z-symmetric fill computes: every texel is in it or mirrors
// one that is (a middle column or row of an odd face mirrors itself).
bool cube_texel_in_z_half(int face, int i, int j, int n);
// Copies every texel outside that half of every cube of `tex` from its
// mirror: for cubes whose content is symmetric about z = 0.
void fill_z_mirrors(Texture& tex);

// The solid angle of texel (i, j) of an n x n face, exact (the area of its
// square on the unit cube projected onto the sphere).
double cube_texel_solid_angle(int i, int j, int n);

// Bilinear read of cube `cube` (layers 6 cube .. 6 cube + 5) in direction d,
// clamped to the edge of the face d selects (the seams differ from a
// seamless read by at most half a texel's gradient). RGB of channels 0-2.
glm::dvec3 sample_cube(const Texture& level, int cube, glm::dvec3 d);
// The same read at a direction's coordinates, for reads of one direction
// in several levels.
glm::dvec3 sample_cube(const Texture& level, int cube, const CubeCoord& c);

}  // namespace skybake

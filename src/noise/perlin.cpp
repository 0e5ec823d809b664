#include "noise/perlin.hpp"

#include <cassert>
#include <cmath>

#include "core/math.hpp"
#include "noise/lattice_hash.hpp"

namespace skybake {
namespace {

// Perlin 2002: the 12 edge midpoints of the cube, no axis favoured.
constexpr float kEdges3[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                  {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                  {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
// Eight directions 45 degrees apart, all of length sqrt 2 (so the 2D range
// matches the 3D one: 1 at a cell centre).
constexpr float kSqrt2 = 1.41421356237f;
constexpr float kDirs2[8][2] = {{kSqrt2, 0},  {1, 1},   {0, kSqrt2},  {-1, 1},
                                {-kSqrt2, 0}, {-1, -1}, {0, -kSqrt2}, {1, -1}};

// Lower lattice corner (wrapped), the next one (wrapped) and the fraction.
struct Axis {
  int i0, i1;
  float f;
};
Axis lattice_axis(float p, int period) {
  assert(period > 0);
  const float fl = std::floor(p);
  const int i = wrap_index(int(fl), period);
  return {i, i + 1 == period ? 0 : i + 1, p - fl};
}

}  // namespace

glm::vec3 perlin3_lattice_gradient(int x, int y, int z, uint32_t seed) {
  const float* g = kEdges3[index_from_hash(hash_lattice(x, y, z, seed), 12)];
  return {g[0], g[1], g[2]};
}

glm::vec2 perlin2_lattice_gradient(int x, int y, uint32_t seed) {
  const float* g = kDirs2[index_from_hash(hash_lattice(x, y, seed), 8)];
  return {g[0], g[1]};
}

NoiseSample3 perlin3_sample(glm::vec3 p, glm::ivec3 period, uint32_t seed) {
  const Axis ax = lattice_axis(p.x, period.x), ay = lattice_axis(p.y, period.y),
             az = lattice_axis(p.z, period.z);
  const glm::vec3 f(ax.f, ay.f, az.f);
  const glm::vec3 s(perlin_fade(f.x), perlin_fade(f.y), perlin_fade(f.z));
  const glm::vec3 ds(perlin_fade_derivative(f.x), perlin_fade_derivative(f.y),
                     perlin_fade_derivative(f.z));
  NoiseSample3 out;
  for (int c = 0; c < 8; ++c) {
    const int cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
    const glm::vec3 g =
        perlin3_lattice_gradient(cx ? ax.i1 : ax.i0, cy ? ay.i1 : ay.i0, cz ? az.i1 : az.i0, seed);
    const glm::vec3 d = f - glm::vec3(cx, cy, cz);
    const float dot = g.x * d.x + g.y * d.y + g.z * d.z;
    // Trilinear weight of this corner and its derivative along each axis.
    const float wx = cx ? s.x : 1.0f - s.x, wy = cy ? s.y : 1.0f - s.y, wz = cz ? s.z : 1.0f - s.z;
    const float dwx = cx ? ds.x : -ds.x, dwy = cy ? ds.y : -ds.y, dwz = cz ? ds.z : -ds.z;
    const float w = wx * wy * wz;
    out.value += w * dot;
    out.gradient += w * g + dot * glm::vec3(dwx * wy * wz, wx * dwy * wz, wx * wy * dwz);
  }
  return out;
}

float perlin3(glm::vec3 p, glm::ivec3 period, uint32_t seed) {
  return perlin3_sample(p, period, seed).value;
}

NoiseSample2 perlin2_sample(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
  const Axis ax = lattice_axis(p.x, period.x), ay = lattice_axis(p.y, period.y);
  const glm::vec2 f(ax.f, ay.f);
  const glm::vec2 s(perlin_fade(f.x), perlin_fade(f.y));
  const glm::vec2 ds(perlin_fade_derivative(f.x), perlin_fade_derivative(f.y));
  NoiseSample2 out;
  for (int c = 0; c < 4; ++c) {
    const int cx = c & 1, cy = c >> 1;
    const glm::vec2 g = perlin2_lattice_gradient(cx ? ax.i1 : ax.i0, cy ? ay.i1 : ay.i0, seed);
    const glm::vec2 d = f - glm::vec2(cx, cy);
    const float dot = g.x * d.x + g.y * d.y;
    const float wx = cx ? s.x : 1.0f - s.x, wy = cy ? s.y : 1.0f - s.y;
    const float dwx = cx ? ds.x : -ds.x, dwy = cy ? ds.y : -ds.y;
    out.value += wx * wy * dot;
    out.gradient += wx * wy * g + dot * glm::vec2(dwx * wy, wx * dwy);
  }
  return out;
}

float perlin2(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
  return perlin2_sample(p, period, seed).value;
}

}  // namespace skybake

// Periodic gradient ("Perlin") noise in 2D and 3D, with its analytic gradient.
//
// Perlin 1985 gradient noise with the quintic fade s(t) = 6t^5 - 15t^4 + 10t^3 of
// Perlin 2002 ("Improving Noise"), which makes the noise C2 so that its
// gradient, and the curl built from it (curl.hpp), is continuous. Tileable
// (docs/reference.md "Cloud noise"): the lattice coordinates are wrapped with a
// floor-based modulo by an integer period per axis before hashing, so
// n(p + period) = n(p) for value and gradient, also for negative p.
//
// Units: p is in lattice cells; the gradient is d n / d p per cell.
// Range: 3D uses Perlin 2002's 12 cube-edge gradients (length sqrt 2) and 2D
// eight directions of length sqrt 2; both reach +-1 at a cell centre when all
// corner gradients point at it, and |n| <= 1 in practice (the provable bound
// from |g . d| <= 2 is 2; the tests check |n| <= 1 on 200k random points).
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace skybake {

struct NoiseSample2 {
  float value = 0;
  glm::vec2 gradient{0};  // per lattice cell
};
struct NoiseSample3 {
  float value = 0;
  glm::vec3 gradient{0};  // per lattice cell
};

// Quintic fade (Perlin 2002) and its derivative 30 t^2 (t - 1)^2.
inline float perlin_fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}
inline float perlin_fade_derivative(float t) {
  const float u = t * (t - 1.0f);
  return 30.0f * u * u;
}

// The gradient at a lattice point whose coordinates are already wrapped into
// [0, period). Public so that the volume bakers build their gradient tables
// from the same definition as the pure functions.
glm::vec3 perlin3_lattice_gradient(int x, int y, int z, uint32_t seed);
glm::vec2 perlin2_lattice_gradient(int x, int y, uint32_t seed);

// Value in about [-1, 1]; period > 0 on every axis (lattice cells).
float perlin2(glm::vec2 p, glm::ivec2 period, uint32_t seed);
float perlin3(glm::vec3 p, glm::ivec3 period, uint32_t seed);

// Value and analytic gradient (same value as perlin2 / perlin3).
NoiseSample2 perlin2_sample(glm::vec2 p, glm::ivec2 period, uint32_t seed);
NoiseSample3 perlin3_sample(glm::vec3 p, glm::ivec3 period, uint32_t seed);

}  // namespace skybake

#include "noise/curl.hpp"

#include <cassert>

#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"

namespace skybake {
namespace {
// Streams 0..2 are the 3D potentials; 3 is the 2D one.
constexpr uint32_t kStream2d = 3;
}  // namespace

NoiseSample2 curl2_potential(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed,
                             float gain) {
  return perlin_fbm2_sample(p, period, octaves, stream_seed(seed, kStream2d), gain);
}

NoiseSample3 curl3_potential(int component, glm::vec3 p, glm::ivec3 period, int octaves,
                             uint32_t seed, float gain) {
  assert(component >= 0 && component < 3);
  return perlin_fbm3_sample(p, period, octaves, stream_seed(seed, uint32_t(component)), gain);
}

glm::vec2 curl2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed, float gain) {
  const glm::vec2 g = curl2_potential(p, period, octaves, seed, gain).gradient;
  return {g.y, -g.x};
}

glm::vec3 curl3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed, float gain) {
  const glm::vec3 d1 = curl3_potential(0, p, period, octaves, seed, gain).gradient;
  const glm::vec3 d2 = curl3_potential(1, p, period, octaves, seed, gain).gradient;
  const glm::vec3 d3 = curl3_potential(2, p, period, octaves, seed, gain).gradient;
  return {d3.y - d2.z, d1.z - d3.x, d2.x - d1.y};
}

}  // namespace skybake

#include "noise/fbm.hpp"

#include <cassert>

#include "noise/lattice_hash.hpp"
#include "noise/worley.hpp"

namespace skybake {

float worley_fbm_weight(int octave, int octaves) {
  assert(octaves >= 1 && octaves <= kMaxOctaves && octave >= 0 && octave < octaves);
  // Schneider's 0.25, 0.125, then halving: 0.5^(o + 1) for o >= 1.
  auto tail = [](int o) { return 1.0f / float(1 << (o + 1)); };
  if (octave > 0) return tail(octave);
  float rest = 0.0f;
  for (int o = 1; o < octaves; ++o) rest += tail(o);
  return 1.0f - rest;
}

NoiseSample3 perlin_fbm3_sample(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed,
                                float gain) {
  assert(octaves >= 1 && octaves <= kMaxOctaves);
  NoiseSample3 sum;
  float amplitude = 1.0f, amplitude_sum = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    const float scale = float(1 << o);  // exact: p * 2^o stays periodic bit for bit
    const glm::ivec3 octave_period = period * (1 << o);
    const NoiseSample3 n = perlin3_sample(p * scale, octave_period,
                                          field_seed(seed, NoiseKind::perlin, octave_period));
    sum.value += amplitude * n.value;
    sum.gradient += (amplitude * scale) * n.gradient;  // chain rule: d/dp n(2^o p)
    amplitude_sum += amplitude;
    amplitude *= gain;
  }
  sum.value /= amplitude_sum;
  sum.gradient /= amplitude_sum;
  return sum;
}

NoiseSample2 perlin_fbm2_sample(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed,
                                float gain) {
  assert(octaves >= 1 && octaves <= kMaxOctaves);
  NoiseSample2 sum;
  float amplitude = 1.0f, amplitude_sum = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    const float scale = float(1 << o);
    const glm::ivec2 octave_period = period * (1 << o);
    const NoiseSample2 n =
        perlin2_sample(p * scale, octave_period,
                       field_seed(seed, NoiseKind::perlin, glm::ivec3(octave_period, 0)));
    sum.value += amplitude * n.value;
    sum.gradient += (amplitude * scale) * n.gradient;
    amplitude_sum += amplitude;
    amplitude *= gain;
  }
  sum.value /= amplitude_sum;
  sum.gradient /= amplitude_sum;
  return sum;
}

float perlin_fbm3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed, float gain) {
  return perlin_fbm3_sample(p, period, octaves, seed, gain).value;
}

float perlin_fbm2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed, float gain) {
  return perlin_fbm2_sample(p, period, octaves, seed, gain).value;
}

float worley_fbm3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed) {
  assert(octaves >= 1 && octaves <= kMaxOctaves);
  float sum = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    const glm::ivec3 octave_period = period * (1 << o);
    sum += worley_fbm_weight(o, octaves) *
           worley3_inverted(p * float(1 << o), octave_period,
                            field_seed(seed, NoiseKind::worley, octave_period));
  }
  return sum;
}

float worley_fbm2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed) {
  assert(octaves >= 1 && octaves <= kMaxOctaves);
  float sum = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    const glm::ivec2 octave_period = period * (1 << o);
    sum += worley_fbm_weight(o, octaves) *
           worley2_inverted(p * float(1 << o), octave_period,
                            field_seed(seed, NoiseKind::worley, glm::ivec3(octave_period, 0)));
  }
  return sum;
}

}  // namespace skybake

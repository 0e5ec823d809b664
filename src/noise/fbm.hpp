// Fractal sums (fBm, Mandelbrot & van Ness 1968) of the periodic noises, as the
// cloud noises use them (Schneider, GPU Pro 7 sec. 4.3.1; Frostbite 2016
// sec. 5.4 and Appendix D).
//
// Octave o has frequency 2^o times the base, so its period is period * 2^o
// lattice cells over the same domain: every octave repeats exactly where the
// base does and the sum tiles (docs/reference.md "Cloud noise": every
// octave's frequency an integer multiple of the base). Each octave is its
// own field, seeded by field_seed(seed, kind, period * 2^o)
// (lattice_hash.hpp).
//
// - Perlin fBm: amplitudes gain^o, divided by their sum so the range stays
//   about [-1, 1] whatever the octave count.
// - Worley fBm: inverted Worley (1 - F1) with Schneider's weights 0.625, 0.25,
//   0.125 over f, 2f, 4f (GPU Pro 7 sec. 4.3.4, the low_freq_FBM sum); in [0, 1].
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "noise/perlin.hpp"

namespace skybake {

// Octave counts allowed everywhere (the finest period is period * 2^7).
constexpr int kMaxOctaves = 8;

// Weight of octave o in a Worley fBm of `octaves` octaves. The tail follows
// Schneider's table 0.625, 0.25, 0.125 and keeps halving after it; the first
// octave takes what the tail leaves, so the weights always sum to 1:
//   1 octave: 1;  2: 0.75, 0.25 (TileableVolumeNoise's two-octave channels);
//   3: 0.625, 0.25, 0.125 (Schneider);  4: 0.5625, 0.25, 0.125, 0.0625.
float worley_fbm_weight(int octave, int octaves);

// Perlin fBm, about [-1, 1]; p and the gradient in cells of the base period.
float perlin_fbm2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed, float gain = 0.5f);
float perlin_fbm3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed, float gain = 0.5f);
NoiseSample2 perlin_fbm2_sample(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed,
                                float gain = 0.5f);
NoiseSample3 perlin_fbm3_sample(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed,
                                float gain = 0.5f);

// Inverted-Worley fBm in [0, 1]; p in cells of the base period.
float worley_fbm2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed);
float worley_fbm3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed);

}  // namespace skybake

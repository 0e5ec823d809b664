// Integer lattice hashing for the periodic noises (docs/reference.md "Cloud
// noise"). Every random quantity of a noise (a Perlin gradient, a Worley feature
// point) is a pure function of (wrapped lattice coordinates, seed): no RNG state,
// so any texel can be computed alone, by any thread, in any order
// (docs/architecture.md "Determinism").
//
// The mixer is Chris Wellons' "lowbias32" integer hash (hash-prospector, 2020),
// an avalanche of two multiply/xorshift rounds with a measured bias of ~0.17,
// lower than murmur3's fmix32. Coordinates are folded in one at a time
// (h = mix(x + mix(y + mix(z + mix(seed))))) so that permuting the axes or
// shifting one coordinate changes every output bit.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace skybake {

inline uint32_t hash_mix(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Lattice coordinates are passed already wrapped into [0, period) (wrap_index):
// wrapping before hashing is what makes the noise periodic.
inline uint32_t hash_lattice(int x, int y, int z, uint32_t seed) {
  uint32_t h = hash_mix(seed);
  h = hash_mix(uint32_t(z) + h);
  h = hash_mix(uint32_t(y) + h);
  return hash_mix(uint32_t(x) + h);
}
inline uint32_t hash_lattice(int x, int y, uint32_t seed) {
  uint32_t h = hash_mix(seed);
  h = hash_mix(uint32_t(y) + h);
  return hash_mix(uint32_t(x) + h);
}

// The top 24 bits as a float in [0, 1): every value is exact in float, and 1 is
// never reached, so a feature point stays inside its cell.
inline float unit_float_from_hash(uint32_t h) {
  return float(h >> 8) * (1.0f / 16777216.0f);
}

// n in [0, count) without the modulo bias of h % count (Lemire 2019).
inline uint32_t index_from_hash(uint32_t h, uint32_t count) {
  return uint32_t((uint64_t(h) * count) >> 32);
}

// Which noise a field belongs to; part of the field seed so that a Perlin
// field and a Worley field with the same seed and period are unrelated.
enum class NoiseKind : uint32_t { perlin = 1, worley = 2, curl_potential = 3 };

// The seed of one noise field (one octave): derived from the user seed, the
// kind and the period only, not from the octave index. Two fBm sums that both
// contain the period-16 Worley field therefore contain the same field, which
// lets the volume bakers evaluate it once (and matches the layout of
// TileableVolumeNoise, where channels share Worley frequencies).
inline uint32_t field_seed(uint32_t seed, NoiseKind kind, glm::ivec3 period) {
  uint32_t h = hash_mix(seed ^ 0x9e3779b9U);
  h = hash_mix(h + uint32_t(kind));
  h = hash_mix(h + uint32_t(period.x));
  h = hash_mix(h + uint32_t(period.y));
  return hash_mix(h + uint32_t(period.z));
}

// A seed derived from another for an independent stream (the three curl
// potentials, the detail volume versus the shape volume).
inline uint32_t stream_seed(uint32_t seed, uint32_t stream) {
  return hash_mix(seed + hash_mix(stream + 0x632be5abU));
}

}  // namespace skybake

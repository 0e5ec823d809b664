// A counter-based random number generator for the path tracer: the stream
// of sample k of a run is a pure function of (seed, k, channel), so a sample
// draws the same numbers whichever thread runs it and in whatever order, and
// estimates are bit-identical for any thread count.
//
// SplitMix64 (Steele, Lea & Flood 2014, the seeding generator of Java's
// SplittableRandom and of xoshiro): output i of a stream is the 64-bit
// finalizer mix64(key + (i + 1) * golden); keys are derived by chaining the
// same finalizer over (seed, stream, substream). It passes BigCrush; two
// streams overlap only if their keys differ by a small multiple of the
// golden gamma, which for hashed keys has probability ~2^-40 per pair.
#pragma once

#include <cstdint>

namespace skybake {

// The SplitMix64 finalizer: a bijective 64-bit mix with full avalanche.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class CounterRng {
 public:
  static constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;

  CounterRng(uint64_t seed, uint64_t stream, uint64_t substream)
      : state_(mix64(mix64(mix64(seed + kGolden) + stream) + substream)) {}

  uint64_t next_u64() {
    state_ += kGolden;
    return mix64(state_);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return double(next_u64() >> 11) * 0x1.0p-53; }
  double operator()() { return uniform(); }

 private:
  uint64_t state_;
};

}  // namespace skybake

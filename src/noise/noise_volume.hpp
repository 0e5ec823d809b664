// The two tileable cloud noise volumes of Schneider's cloud system and their
// packed single-channel variants (docs/reference.md "Cloud noise").
//
//   noise_shape   128^3 RGBA (Schneider, GPU Pro 7 sec. 4.3.1 figure 4.8; SIGGRAPH
//                 2015 slides): R = Perlin-Worley, G, B, A = inverted-Worley fBm
//                 at increasing frequencies. Read by the sampler as the base shape.
//   noise_detail  32^3 RGB (figure 4.9): inverted-Worley fBm at increasing
//                 frequencies; erodes the base shape.
//
// Defaults follow the generator Frostbite's Appendix D points to
// (TileableVolumeNoise, main.cpp), which fixes the numbers the papers leave out:
//   shape:  Perlin fBm period 8, 3 octaves (8, 16, 32); the Perlin-Worley's
//           Worley fBm period 8 (its lowest Worley frequency is 8 there too);
//           G, B, A Worley fBm periods 8, 16, 32 with 3, 3, 2 octaves.
//   detail: R, G, B Worley fBm periods 2, 4, 8 with 3, 3, 2 octaves.
// The last channel of each has 2 octaves (weights 0.75, 0.25, fbm.hpp) for the
// reason TileableVolumeNoise gives: a third octave would have one cell per
// voxel and alias. spec_problems() enforces that rule for every channel (the
// finest period is at most size / 2 cells, i.e. a cell spans >= 2 voxels).
// Periods are cells (or lattice cells) across the whole volume, so every
// channel tiles on every axis.
//
// Layout: Texture (core/texture.hpp), channel fastest, then x, y, z. Values in
// [0, 1]. Threading: tbb::parallel_for over z slices, every voxel computed
// independently: identical output for any thread count. Random numbers come
// from tables built per bake (volume_rows.hpp), which is what makes the full
// set (shape + detail + curl) bake in tens of milliseconds.
// Errors: a spec that spec_problems() rejects makes the bakers throw Error
// (the pipeline validates presets first, so reaching it is a bug).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "noise/perlin_worley.hpp"

namespace skybake {

// An inverted-Worley fBm channel: octave o has period * 2^o cells across the
// volume, weighted by worley_fbm_weight (0.625, 0.25, 0.125 for 3 octaves).
struct WorleyFbmSpec {
  int period = 8;   // cells across the volume of the first octave
  int octaves = 3;  // 1 .. kMaxOctaves
};

struct NoiseShapeSpec {
  int size = 128;                     // voxels per axis (a cube)
  uint32_t seed = 0;                  // any value; same seed, same volume
  int perlin_period = 8;              // R: Perlin fBm, lattice cells across the volume
  int perlin_octaves = 3;             // R: Perlin fBm octaves
  float perlin_gain = 0.5f;           // R: amplitude ratio between octaves, (0, 1]
  WorleyFbmSpec perlin_worley{8, 3};  // R: the Worley fBm that dilates the Perlin fBm
  PerlinWorleyRemap remap = PerlinWorleyRemap::worley_new_min;      // R: see perlin_worley.hpp
  std::array<WorleyFbmSpec, 3> worley{{{8, 3}, {16, 3}, {32, 2}}};  // G, B, A
};

struct NoiseDetailSpec {
  int size = 32;                                                  // voxels per axis
  uint32_t seed = 0;                                              // any value
  std::array<WorleyFbmSpec, 3> worley{{{2, 3}, {4, 3}, {8, 2}}};  // R, G, B
};

// The detail volume draws its fields from stream_seed(seed, kDetailStream), so
// that a shape and a detail volume baked with the same seed are unrelated even
// where they share a Worley period. The shape volume uses the seed as given.
constexpr uint32_t kDetailStream = 0x64657461;  // "deta"

// One rejected field: `field` names the spec member ("size",
// "worley[2].octaves"), `message` says what was expected and what was got.
struct SpecProblem {
  std::string field;
  std::string message;
};
std::vector<SpecProblem> spec_problems(const NoiseShapeSpec& spec);
std::vector<SpecProblem> spec_problems(const NoiseDetailSpec& spec);

// Channels "R", "G", "B", "A"; metadata: product, seed, per channel its meaning
// ("channel.R"), base period ("period.R") and octaves ("octaves.R"), remap.
Texture bake_noise_shape(const NoiseShapeSpec& spec, const BakeContext& ctx);
// Channels "R", "G", "B"; metadata as for the shape volume.
Texture bake_noise_detail(const NoiseDetailSpec& spec, const BakeContext& ctx);

// Packing into one channel (Frostbite 2016 sec. 5.4: "we simply use a single
// component volume texture representing the final single channel noise"), with
// the formulas of TileableVolumeNoise's packed outputs:
//   dilate_base:   fbm = w[1] G + w[2] B + w[3] A;
//                  out = saturate(remap(R, -(1 - fbm), 1, 0, 1))
//                      = saturate((R + 1 - fbm) / (2 - fbm))   (w[0] unused)
//                  i.e. the GPU Pro 7 sampler's base_cloud, baked (shape volume).
//   weighted_sum:  out = saturate(sum_c w[c] channel_c)      (detail volume).
enum class PackMode { dilate_base, weighted_sum };
struct PackWeights {
  PackMode mode = PackMode::weighted_sum;
  std::array<float, 4> weights{{0.625f, 0.25f, 0.125f, 0.0f}};  // per input channel
};
// Schneider's low_freq_FBM / high_freq_FBM weights (GPU Pro 7 sec. 4.3.4).
inline PackWeights shape_pack_weights() {
  return {PackMode::dilate_base, {{0.0f, 0.625f, 0.25f, 0.125f}}};
}
inline PackWeights detail_pack_weights() {
  return {PackMode::weighted_sum, {{0.625f, 0.25f, 0.125f, 0.0f}}};
}
// One channel "R", same shape; metadata copied, plus "packed" (the formula).
// Throws Error when dilate_base gets fewer than 2 channels.
Texture pack_single_channel(const Texture& tex, PackWeights weights);

}  // namespace skybake

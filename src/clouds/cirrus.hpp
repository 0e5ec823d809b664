// High-altitude cloud templates: the scrolling 2D textures that stand in for
// cirrus and alto clouds above the volumetric layer (Schneider, GPU Pro 7
// sec. 4.5.4: "a 512^2 texture with three channels"; SIGGRAPH 2015 slides,
// "various types of cirrus and alto clouds that were tiling and scrolling").
//
//   R  cirrus streaks       ridged Perlin fBm, 1 - |n|, stretched: fewer
//                           cells along x than along y, so the fibres run
//                           along x (rotate the UVs in the shader for another
//                           wind direction)
//   G  cirrocumulus cells   inverted Worley fBm (1 - F1): small bright cells
//   B  altostratus sheets   low-frequency Perlin fBm: broad smooth sheets
//
// Each layer has an integer number of cells across the texture per axis
// (`period`), so every octave repeats exactly and the texture tiles; the
// stretch of the streaks is period.y / period.x. Each channel is then
// remapped with keep_top_fraction (field_stats.hpp): exactly round(coverage
// N) texels are above 0 (N = width x height, distinct values), the largest
// is 1, so values span [0, 1] and coverage is an exact artist's control.
// Octaves whose cells would span fewer than 2 texels on either axis are
// dropped (metadata octaves_used.*): they would only alias.
// Shape: width x height (default 512^2), 3 channels, values in [0, 1].
// Threading: tbb::parallel_for over rows; identical output for any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "noise/noise_volume.hpp"  // SpecProblem

namespace skybake {

struct CirrusLayer {
  glm::ivec2 period{4, 4};  // cells across the texture on x and y, first octave, 1 .. 256
  int octaves = 3;          // 1 .. 8; octave o has period * 2^o cells
  double coverage = 0.5;    // fraction of texels above 0, [0, 1]
};

struct CirrusSpec {
  int width = 512;                             // texels on x
  int height = 512;                            // texels on y
  uint32_t seed = 0;                           // any value; same seed, same texture
  CirrusLayer streaks{{3, 24}, 4, 0.5};        // R: cirrus, stretched 8:1 along x
  CirrusLayer cirrocumulus{{16, 16}, 2, 0.4};  // G: cells
  CirrusLayer altostratus{{2, 2}, 4, 0.7};     // B: sheets
};

std::vector<SpecProblem> spec_problems(const CirrusSpec& spec);

// Channels "R", "G", "B"; metadata: product, seed, per channel its meaning,
// periods, octaves and coverage. Throws Error when spec_problems() is not empty.
Texture bake_cirrus(const CirrusSpec& spec, const BakeContext& ctx);

}  // namespace skybake

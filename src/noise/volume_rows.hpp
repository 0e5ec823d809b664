// Row-at-a-time evaluation of one periodic Perlin or Worley field on a cubic
// voxel grid: the fast path of the noise volume bakers (noise_volume.hpp).
// The values are those of perlin3 / worley3_inverted (same hash, same feature
// points); only the order of work changes:
//
// - Random numbers are tabulated once per bake (period^3 gradients or feature
//   points), never hashed in the inner loop.
// - Along a row of voxels (fixed y, z) everything that depends on y and z
//   alone is computed once per row: for Worley, the squared y-z distance q of
//   every feature point of the 3x3 neighbour cells of each x column, keeping
//   only q < 1 (a point with q >= 1 is beyond the clamp bound of worley.hpp for
//   every voxel of the row), so a voxel scans ~8 candidates instead of 27;
//   for Perlin, the y-z interpolated gradient terms of each lattice column,
//   leaving ~10 flops per voxel and octave.
// - Neighbouring voxels of a row share their candidates and are scanned
//   together in the lanes of one vector, of one cell or several
//   (noise/kernels/worley_nearest.hpp); distances are cell-local with
//   worley3_f1's expressions, so the baked Worley values equal the pure
//   function's bit for bit on every SIMD target.
// Voxel i of n sits at the texel centre (i + 0.5) / n of the unit domain, i.e.
// at cell_coord_from_texel(i, n, period) in cells.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace skybake {

// Texel centre of voxel i of n in cells of a field with `period` cells across.
inline float cell_coord_from_texel(int i, int n, int period) {
  return (float(i) + 0.5f) * float(period) / float(n);
}

// Per-thread buffers of the row evaluators; reused across rows, so no
// allocation happens per voxel or per row once they have grown.
struct RowScratch {
  std::vector<float> a, b, c, d;
  std::vector<int> start;
};

class WorleyRows {
 public:
  // size: voxels per axis; period: cells per axis; seed: the field seed
  // (field_seed(..., NoiseKind::worley, {period, period, period})).
  WorleyRows(int size, int period, uint32_t seed);
  int period() const { return period_; }
  // out[x] = worley3_inverted at voxel (x, y, z), x in [0, size).
  void eval_row(int y, int z, RowScratch& scratch, float* out) const;

 private:
  int size_, period_;
  // Feature point offset per cell, x fastest; one array per axis so that
  // rows of cells load as contiguous floats.
  std::vector<float> offset_x_, offset_y_, offset_z_;
  std::vector<float> frac_;      // voxel centre per index, in its cell (7 extra: SIMD lanes)
  std::vector<float> cell_f_;    // cell_ as floats (7 extra: the last cell again)
  std::vector<int> cell_;        // the cell of the voxel centre
  std::vector<int> cell_begin_;  // first voxel of each cell; [period] = size
};

class PerlinRows {
 public:
  // seed: the field seed (field_seed(..., NoiseKind::perlin, {period, ...})).
  PerlinRows(int size, int period, uint32_t seed);
  // out[x] += amplitude * perlin3 at voxel (x, y, z).
  void accumulate_row(int y, int z, float amplitude, RowScratch& scratch, float* out) const;

 private:
  int size_, period_;
  std::vector<glm::vec3> gradients_;  // per lattice point, x fastest
  std::vector<float> frac_, fade_;    // per voxel index: position in its cell, fade of it
  std::vector<int> cell_;             // per voxel index: lattice cell (wrapped)
  std::vector<int> cell_begin_;       // first voxel of each cell; [period] = size
};

}  // namespace skybake

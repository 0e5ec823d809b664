// The noise layer's kernels on every SIMD target against the pure
// functions, bit for bit: the row evaluator of the Worley volumes
// (noise/volume_rows.hpp, noise/kernels/worley_nearest.hpp) against
// worley3_inverted at every voxel of whole rows. Sizes that are no multiple
// of the period or of 8 leave cells of uneven voxel counts, lanes past the
// row and groups of 8 voxels that straddle up to 8 cells.
#include "noise/volume_rows.hpp"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "noise/lattice_hash.hpp"
#include "noise/worley.hpp"
#include "support/simd_targets.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

// Counts the voxels of rows (y, z) whose value differs in any bit from
// worley3_inverted at the voxel's texel centre.
int mismatches(int size, int period) {
  const uint32_t seed = field_seed(7, NoiseKind::worley, glm::ivec3(period));
  const WorleyRows rows(size, period, seed);
  RowScratch scratch;
  std::vector<float> out(static_cast<size_t>(size));
  int bad = 0;
  for (int z = 0; z < size; z += 3)
    for (int y = 0; y < size; y += 2) {
      rows.eval_row(y, z, scratch, out.data());
      for (int x = 0; x < size; ++x) {
        const glm::vec3 p(cell_coord_from_texel(x, size, period),
                          cell_coord_from_texel(y, size, period),
                          cell_coord_from_texel(z, size, period));
        const float expected = worley3_inverted(p, glm::ivec3(period), seed);
        bad += std::memcmp(&out[size_t(x)], &expected, sizeof(float)) != 0;
      }
    }
  return bad;
}

TEST_P(KernelsOnEachTarget, WorleyRowsAreThePureFunction) {
  struct Case {
    int size, period;
  };
  for (const Case c : {Case{32, 2}, Case{32, 16}, Case{37, 5}, Case{21, 8}, Case{16, 8},
                       Case{40, 20}, Case{13, 1}, Case{64, 32}, Case{11, 3}})
    EXPECT_EQ(mismatches(c.size, c.period), 0) << "size " << c.size << " period " << c.period;
}

SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET();

}  // namespace
}  // namespace skybake

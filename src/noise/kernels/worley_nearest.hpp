// The inner loop of the Worley rows (noise/volume_rows.hpp): for every voxel
// of a row, 1 - the distance to the nearest feature point among a row's
// compacted candidates, over lanes (Highway, every target from one source).
#pragma once

namespace skybake {

// out[x] = 1 - sqrt(min(1, min_k (frac[x] - ((col[k] - cell_f[x]) + ox[k]))^2
// + q[k]))) for x < size, k over the candidates of the columns cell[x] - 1 ..
// cell[x] + 1, which are [start[cell[x]], start[cell[x] + 3]) (candidate k
// of column col[k], its x offset ox[k] and squared y-z distance q[k]).
// frac and cell_f hold 7 entries past size (lanes past the row stay in its
// last cell). A lane scans every column from the first lane's cell - 1 to
// the last lane's + 1: a column two or more cells away gives d2 >= 1 (f and
// ox are in [0, 1)), which cannot lower the bound, so the same minimum,
// bit for bit on every target (tests/noise/kernels_test.cpp).
void worley_nearest_row(const float* frac, const float* cell_f, const int* cell, int size,
                        const float* ox, const float* q, const float* col, const int* start,
                        float* out);

}  // namespace skybake

#include "noise/volume_rows.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/math.hpp"
#include "noise/kernels/worley_nearest.hpp"
#include "noise/perlin.hpp"
#include "noise/worley.hpp"

namespace skybake {
namespace {

// f(z) for every plane z of a period^3 table, planes side by side: a table
// is one hash per cell, and the largest (64^3 cells for the default shape
// volume, a few ms) would otherwise stand alone before the bake's loop.
// Each cell is written once from its own coordinates: the same table for
// any thread count. Below 4096 cells a task, the planes stay together.
template <typename F>
void for_each_plane(int period, const F& f) {
  const size_t plane = size_t(period) * size_t(period);
  const int grain = int(std::max<size_t>(1, 4096 / plane));
  tbb::parallel_for(tbb::blocked_range<int>(0, period, grain),
                    [&](const tbb::blocked_range<int>& zs) {
                      for (int z = zs.begin(); z < zs.end(); ++z) f(z);
                    });
}

}  // namespace

WorleyRows::WorleyRows(int size, int period, uint32_t seed)
    : size_(size),
      period_(period),
      frac_(size + 7),
      cell_f_(size + 7),
      cell_(size),
      cell_begin_(period + 1) {
  assert(size > 0 && period > 0);
  const size_t cells = size_t(period) * period * period;
  for (auto* a : {&offset_x_, &offset_y_, &offset_z_}) a->resize(cells);
  for_each_plane(period, [&](int z) {
    for (int y = 0; y < period; ++y)
      for (int x = 0; x < period; ++x) {
        const size_t i = (size_t(z) * period + y) * period + x;
        const glm::vec3 o = worley3_feature_offset(x, y, z, seed);
        offset_x_[i] = o.x;
        offset_y_[i] = o.y;
        offset_z_[i] = o.z;
      }
  });
  // cell_begin_[c] = first voxel whose centre lies in cell c (coordinates increase).
  int c = 0;
  for (int i = 0; i < size + 7; ++i) {
    const float u = cell_coord_from_texel(i, size, period), fl = std::floor(u);
    frac_[i] = u - fl;  // exact
    cell_f_[i] = i < size ? fl : cell_f_[size - 1];  // lanes past the row stay in its last cell
    if (i >= size) continue;
    cell_[i] = int(fl);
    while (c <= cell_[i]) cell_begin_[c++] = i;
  }
  while (c <= period) cell_begin_[c++] = size;
}

void WorleyRows::eval_row(int y, int z, RowScratch& s, float* out) const {
  const int p = period_;
  const float fy = frac_[y], fz = frac_[z];
  const int cy = cell_[y], cz = cell_[z];
  // Candidates of x column cx (cx = -1 .. p, unwrapped) are ox/q[start[cx + 1],
  // start[cx + 2]): x offset in the cell and squared y-z distance. ox/q are
  // sized for every candidate and more: the branch-free compaction writes
  // one past the last.
  const size_t max_candidates = size_t(p + 2) * 9 + 8;
  if (s.a.size() < max_candidates) s.a.resize(max_candidates), s.b.resize(max_candidates);
  if (s.c.size() < size_t(p) * 9) s.c.resize(size_t(p) * 9);
  if (s.start.size() < size_t(p + 3)) s.start.resize(p + 3);
  if (s.d.size() < max_candidates) s.d.resize(max_candidates);
  float* ox = s.a.data();
  float* q = s.b.data();
  float* qj = s.c.data();  // [j][wx]: q of the 9 y-z neighbours j of every column
  float* col_of = s.d.data();  // the column cx of each candidate
  // First the y-z distances, neighbour by neighbour along contiguous table
  // rows (vectorized), with the expressions of worley3_f1 (cell-local), so
  // the values are bit-identical.
  size_t rows[9];
  for (int j = 0; j < 9; ++j) {
    const int oy = j % 3 - 1, oz = j / 3 - 1;
    rows[j] = (size_t(wrap_index(cz + oz, p)) * p + wrap_index(cy + oy, p)) * p;
    const float* oy_row = &offset_y_[rows[j]];
    const float* oz_row = &offset_z_[rows[j]];
    const float sy = float(oy), sz = float(oz);
    float* qrow = qj + size_t(j) * p;
    for (int x = 0; x < p; ++x) {
      const float dy = fy - (sy + oy_row[x]);
      const float dz = fz - (sz + oz_row[x]);
      qrow[x] = dy * dy + dz * dz;
    }
  }
  // Then the compaction, column by column, of the points with q < 1.
  int count = 0;
  for (int col = 0; col < p + 2; ++col) {
    const int cx = col - 1, wx = cx < 0 ? cx + p : (cx >= p ? cx - p : cx);
    s.start[col] = count;
    for (int j = 0; j < 9; ++j) {
      const float qyz = qj[size_t(j) * p + wx];
      // Branch-free: the test is close to a coin flip.
      ox[count] = offset_x_[rows[j] + wx];
      q[count] = qyz;
      col_of[count] = float(cx);
      count += qyz < 1.0f;
    }
  }
  s.start[p + 2] = count;
  worley_nearest_row(frac_.data(), cell_f_.data(), cell_.data(), size_, ox, q, col_of,
                     s.start.data(), out);
}

PerlinRows::PerlinRows(int size, int period, uint32_t seed)
    : size_(size), period_(period), frac_(size), fade_(size), cell_(size), cell_begin_(period + 1) {
  assert(size > 0 && period > 0);
  gradients_.resize(size_t(period) * period * period);
  for_each_plane(period, [&](int z) {
    for (int y = 0; y < period; ++y)
      for (int x = 0; x < period; ++x)
        gradients_[(size_t(z) * period + y) * period + x] = perlin3_lattice_gradient(x, y, z, seed);
  });
  for (int i = 0; i < size; ++i) {
    const float u = cell_coord_from_texel(i, size, period);
    const float fl = std::floor(u);
    cell_[i] = wrap_index(int(fl), period);
    frac_[i] = u - fl;
    fade_[i] = perlin_fade(frac_[i]);
  }
  // Texel centres lie in [0, period) cells and increase: the voxels of
  // cell c are [cell_begin_[c], cell_begin_[c + 1]).
  int c = 0;
  for (int i = 0; i < size; ++i)
    while (c <= cell_[i]) cell_begin_[c++] = i;
  while (c <= period) cell_begin_[c++] = size;
}

void PerlinRows::accumulate_row(int y, int z, float amplitude, RowScratch& s, float* out) const {
  const int p = period_;
  // Column c of the lattice contributes (x - c) * gx[c] + rest[c] at voxel x,
  // where gx and rest are the y-z bilinear blends of its 4 corners' gradient
  // terms; column p is column 0 again (wrapped).
  if (s.a.size() < size_t(p + 1)) s.a.resize(p + 1), s.b.resize(p + 1);
  float* gx = s.a.data();
  float* rest = s.b.data();
  const int y0 = cell_[y], y1 = y0 + 1 == p ? 0 : y0 + 1;
  const int z0 = cell_[z], z1 = z0 + 1 == p ? 0 : z0 + 1;
  const float fy = frac_[y], fz = frac_[z], sy = fade_[y], sz = fade_[z];
  const int ys[2] = {y0, y1}, zs[2] = {z0, z1};
  const float wy[2] = {1.0f - sy, sy}, wz[2] = {1.0f - sz, sz};
  const float dy[2] = {fy, fy - 1.0f}, dz[2] = {fz, fz - 1.0f};
  for (int c = 0; c < p; ++c) {
    float g = 0.0f, r = 0.0f;
    for (int j = 0; j < 4; ++j) {
      const int a = j & 1, b = j >> 1;
      const glm::vec3& grad = gradients_[(size_t(zs[b]) * p + ys[a]) * p + c];
      const float w = wy[a] * wz[b];
      g += w * grad.x;
      r += w * (grad.y * dy[a] + grad.z * dz[b]);
    }
    gx[c] = g;
    rest[c] = r;
  }
  gx[p] = gx[0];
  rest[p] = rest[0];
  // Cell by cell: the voxels of one cell share its two columns, so the
  // inner loop reads contiguous arrays and vectorizes (the same operations
  // per voxel).
  for (int c = 0; c < p; ++c) {
    const float g0 = gx[c], r0 = rest[c], g1 = gx[c + 1], r1 = rest[c + 1];
    for (int x = cell_begin_[c], x_end = cell_begin_[c + 1]; x < x_end; ++x) {
      const float f = frac_[x], sx = fade_[x];
      const float n0 = f * g0 + r0;
      const float n1 = (f - 1.0f) * g1 + r1;
      out[x] += amplitude * (n0 + sx * (n1 - n0));
    }
  }
}

}  // namespace skybake

#include "noise/volume_rows.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/math.hpp"
#include "core/wide_intrinsics.hpp"
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

// value[l] = 1 - sqrt(min(1, min_k (f[l] - (shift_k + ox[k]))^2 + q[k])) for 4
// voxels of one cell at cell-local positions f, where the candidates k of
// the columns c - 1, c, c + 1 are [start[0], start[1]), [start[1], start[2]),
// [start[2], start[3]) with shift_k = -1, 0, +1.
// Explicit SSE where available: GCC vectorizes neither the 4 lanes nor (errno)
// the square root by itself. Two accumulators halve the chain of dependent
// minima; a minimum is exact, so the split changes no bit. Every lane
// operation is an IEEE single-precision operation like the scalar fallback's
// and worley3_f1's, so all give the same bits.
void nearest4(const float* f, const float* ox, const float* q, const int* start, float* value) {
#if defined(__SSE2__)
  const __m128 fs = _mm_loadu_ps(f);
  __m128 b0 = _mm_set1_ps(1.0f), b1 = b0;  // the clamp bound (worley.hpp)
  auto d2 = [&](int k, float shift) {
    const __m128 dx = _mm_sub_ps(fs, _mm_set1_ps(shift + ox[k]));
    return _mm_add_ps(_mm_mul_ps(dx, dx), _mm_set1_ps(q[k]));
  };
  for (int j = 0; j < 3; ++j) {
    const float shift = float(j - 1);
    int k = start[j];
    for (; k + 1 < start[j + 1]; k += 2) {
      b0 = _mm_min_ps(d2(k, shift), b0);
      b1 = _mm_min_ps(d2(k + 1, shift), b1);
    }
    if (k < start[j + 1]) b0 = _mm_min_ps(d2(k, shift), b0);
  }
  _mm_storeu_ps(value, _mm_sub_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(_mm_min_ps(b0, b1))));
#else
  float best[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  for (int j = 0; j < 3; ++j)
    for (int k = start[j]; k < start[j + 1]; ++k)
      for (int l = 0; l < 4; ++l) {
        const float dx = f[l] - (float(j - 1) + ox[k]);
        const float d2 = dx * dx + q[k];
        best[l] = d2 < best[l] ? d2 : best[l];
      }
  for (int l = 0; l < 4; ++l) value[l] = 1.0f - std::sqrt(best[l]);
#endif
}

#if SKYBAKE_HAS_AVX2
// The whole row 8 voxels at a time, whatever cells they fall in: lane l
// (voxel x0 + l, cell cell[x0 + l]) scans the candidates of every column
// from cell[x0] - 1 to cell[x0 + 7] + 1, a contiguous range of the
// compacted arrays, with its own shift col[k] - cell (an exact integer), so
// the lanes of one cell compute nearest4's d2 bit for bit. A column two or
// more cells away from a lane's cell gives that lane d2 >= 1 (|dx| >= 1:
// f and ox are in [0, 1)), which cannot lower the bound: the same minimum.
// Small cells (2 or 4 voxels, periods 64 and 32 of a 128 volume) then
// fill all 8 lanes instead of 4 lanes of which half are dropped.
// d2 of 8 voxels at cell-local positions fs in cells cs to a candidate of
// column col: nearest4's expression with the shift col - cs per lane.
// Always inlined: a 256-bit value passed to a call would change its ABI.
SKYBAKE_AVX2 inline __attribute__((always_inline)) __m256 worley_d2_avx2(__m256 fs, __m256 cs,
                                                                        float col, float ox,
                                                                        float q) {
  const __m256 shift = _mm256_sub_ps(_mm256_set1_ps(col), cs);
  const __m256 dx = _mm256_sub_ps(fs, _mm256_add_ps(shift, _mm256_set1_ps(ox)));
  return _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_set1_ps(q));
}

// For every 8-bit mask, the lanes of its set bits in increasing order, then
// the others: _mm256_permutevar8x32_ps with it moves the kept values to the
// front, in order.
struct LeftPack {
  alignas(32) int lanes[256][8];
  LeftPack() {
    for (int m = 0; m < 256; ++m) {
      int n = 0;
      for (int l = 0; l < 8; ++l)
        if (m & (1 << l)) lanes[m][n++] = l;
      for (int l = 0; l < 8; ++l)
        if (!(m & (1 << l))) lanes[m][n++] = l;
    }
  }
};
const LeftPack kLeftPack;

// eval_row's compaction, column by column: the y-z neighbours j = 0 .. 7 of
// a column gathered at once, those with q < 1 moved to the front in j
// order, then j = 8: the same candidates in the same order as the scalar
// loop. Writes up to 8 floats past the last candidate. Returns the count.
SKYBAKE_AVX2 int compact_columns_avx2(const float* qj, const float* offset_x, const size_t* rows,
                                      int p, float* ox, float* q, float* col_of, int* start) {
  const __m256i q_index = _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
                                             _mm256_set1_epi32(p));
  const __m256i x_index = _mm256_setr_epi32(int(rows[0]), int(rows[1]), int(rows[2]),
                                            int(rows[3]), int(rows[4]), int(rows[5]),
                                            int(rows[6]), int(rows[7]));
  const __m256 one = _mm256_set1_ps(1.0f);
  int count = 0;
  for (int col = 0; col < p + 2; ++col) {
    const int cx = col - 1, wx = cx < 0 ? cx + p : (cx >= p ? cx - p : cx);
    start[col] = count;
    const __m256 qv = _mm256_i32gather_ps(qj + wx, q_index, 4);
    const __m256 xv = _mm256_i32gather_ps(offset_x + wx, x_index, 4);
    const int mask = _mm256_movemask_ps(_mm256_cmp_ps(qv, one, _CMP_LT_OQ));
    const __m256i lanes =
        _mm256_load_si256(reinterpret_cast<const __m256i*>(kLeftPack.lanes[mask]));
    _mm256_storeu_ps(q + count, _mm256_permutevar8x32_ps(qv, lanes));
    _mm256_storeu_ps(ox + count, _mm256_permutevar8x32_ps(xv, lanes));
    _mm256_storeu_ps(col_of + count, _mm256_set1_ps(float(cx)));
    count += __builtin_popcount(unsigned(mask));
    const float q8 = qj[size_t(8) * p + wx];
    ox[count] = offset_x[rows[8] + wx];
    q[count] = q8;
    col_of[count] = float(cx);
    count += q8 < 1.0f;
  }
  start[p + 2] = count;
  return count;
}

SKYBAKE_AVX2 void nearest_row_avx2(const float* frac, const float* cell_f, const int* cell,
                                   int size, const float* ox, const float* q, const float* col,
                                   const int* start, float* out) {
  const __m256 one = _mm256_set1_ps(1.0f);
  for (int x0 = 0; x0 < size; x0 += 8) {
    const int last = std::min(x0 + 7, size - 1);
    const int k_end = start[cell[last] + 3];
    const __m256 fs = _mm256_loadu_ps(frac + x0), cs = _mm256_loadu_ps(cell_f + x0);
    __m256 b0 = one, b1 = one;
    int k = start[cell[x0]];
    for (; k + 1 < k_end; k += 2) {
      b0 = _mm256_min_ps(worley_d2_avx2(fs, cs, col[k], ox[k], q[k]), b0);
      b1 = _mm256_min_ps(worley_d2_avx2(fs, cs, col[k + 1], ox[k + 1], q[k + 1]), b1);
    }
    if (k < k_end) b0 = _mm256_min_ps(worley_d2_avx2(fs, cs, col[k], ox[k], q[k]), b0);
    const __m256 value = _mm256_sub_ps(one, _mm256_sqrt_ps(_mm256_min_ps(b0, b1)));
    if (x0 + 8 <= size) {
      _mm256_storeu_ps(out + x0, value);
    } else {
      float lanes[8];
      _mm256_storeu_ps(lanes, value);
      std::copy(lanes, lanes + (size - x0), out + x0);
    }
  }
}
#endif

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
  // sized for every candidate plus 8: the compactions below write past the last.
  const size_t max_candidates = size_t(p + 2) * 9 + 8;  // + 8: compact_columns_avx2
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
#if SKYBAKE_HAS_AVX2
  if (avx2_enabled()) {
    compact_columns_avx2(qj, offset_x_.data(), rows, p, ox, q, col_of, s.start.data());
    nearest_row_avx2(frac_.data(), cell_f_.data(), cell_.data(), size_, ox, q, col_of,
                     s.start.data(), out);
    return;
  }
#endif
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
  // Voxels of one cell share their candidates: 4 voxels at a time (lanes past
  // the cell are computed and dropped). Columns c - 1, c, c + 1 are shifted by
  // -1, 0, +1 cell relative to the voxels' cell.
  for (int c = 0; c < p; ++c) {
    for (int x0 = cell_begin_[c], x_end = cell_begin_[c + 1]; x0 < x_end; x0 += 4) {
      float value[4];
      nearest4(&frac_[x0], ox, q, &s.start[c], value);
      for (int l = 0, lanes = std::min(4, x_end - x0); l < lanes; ++l) out[x0 + l] = value[l];
    }
  }
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

// Mip chains for DDS output: every level halves each axis (floor, min 1) down
// to 1x1(x1), the convention of D3D/DDS mip chains (Microsoft, "Programming
// Guide for DDS": each mip level is half the size of the previous one).
//
// Filter: an area-weighted box. Output texel j of an axis going from n_in to
// n_out texels covers the input interval [j * n_in / n_out, (j+1) * n_in / n_out)
// (texel units) and averages the input texels weighted by their overlap with
// it. For even sizes that is the classic 2x box (2 texels per axis: 2x2 in 2D,
// 2x2x2 in 3D); for odd sizes the footprint is 2 + 1/n_out texels wide, e.g.
// 5 -> 2 gives (t0 + t1 + t2/2) / 2.5 and (t2/2 + t3 + t4) / 2.5. The footprints
// of one level tile the axis exactly, so every level preserves the mean for any
// size and a periodic (tileable) texture stays periodic at every level.
// Layers of a 2D array are filtered independently; the weights are separable,
// applied one axis at a time.
#pragma once

#include <vector>

#include "core/texture.hpp"

namespace skybake {

// How a filter footprint that reaches past an edge finds its texels: wrap
// (floor-based modulo, for tileable textures) or clamp to the edge texel.
// The area box never reaches past an edge (its footprints partition the
// axis), so both modes give identical results; the mode is part of the API so
// that a wider filter can be added without changing callers.
enum class MipEdge { wrap, clamp };

// Number of levels of a full chain: 1 + floor(log2(max(w, h, d))).
int mip_count(int width, int height, int depth = 1);

// The full chain, level 0 (a copy of `level0`) first, down to 1x1(x1). Each
// level keeps the layers, channel names and metadata of level 0. Runs the
// per-row work with tbb::parallel_for; the result does not depend on the
// thread count.
std::vector<Texture> build_mip_chain(const Texture& level0, MipEdge edge);
// The same chain without level 0: level 1 first (empty for a 1x1x1 texture).
std::vector<Texture> build_lower_mips(const Texture& level0, MipEdge edge);

}  // namespace skybake

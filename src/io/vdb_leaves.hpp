// The trees of a texture's VDB grids built leaf by leaf straight from the
// texture (VDB plugin only: includes OpenVDB). vdb.cpp's reference build
// copies each channel into a dense array and runs OpenVDB's copyFromDense,
// then activates the texture's box; that costs a 4-byte-per-voxel copy of
// every channel (fresh pages) and another walk over it. Where the result
// is provably that same tree, the leaves are filled here instead.
//
// What copyFromDense makes (openvdb/tools/Dense.h, CopyFromDense and
// LeafNode::copyFromDense, tolerance 0, background 0): one leaf per 8^3 block
// of the box; a voxel equal to the background (0 or -0) stored as +0 and
// inactive, any other value as it is and active; a block whose 512 values
// and states are all equal becomes a tile instead (then pruned). The union
// with the all-active box turns every voxel of the box on. So when every
// side is a multiple of 8 (no partial blocks) and no block is constant, the
// tree is: one leaf per block, every voxel active, the texel's value with -0
// as +0, internal nodes made by addLeaf (background tiles, inactive). Any
// other texture, or a channel with a constant block, takes the reference
// build. Tested to give the same file bytes (tests/io/vdb_leaves_test.cpp).
#pragma once

#include <openvdb/openvdb.h>

#include "core/texture.hpp"

namespace skybake {

// Channel c's tree, or a null pointer where the direct build does not apply
// (a side not a multiple of 8, a 2D array, a constant block). The leaves are
// allocated by the calling thread (memory freed by its earlier trees is
// reused, io/vdb_archive.hpp) and filled by TBB's threads.
openvdb::FloatTree::Ptr direct_leaf_tree(const Texture& tex, int c);

}  // namespace skybake

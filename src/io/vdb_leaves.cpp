#include "io/vdb_leaves.hpp"

#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace skybake {

namespace {

using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;
constexpr int kLeafDim = int(Leaf::DIM);  // 8: a leaf is an 8^3 block
static_assert(Leaf::LOG2DIM == 3, "the offset below is (x << 6) | (y << 3) | z");

struct Blocks {
  int nx, ny, nz;  // blocks per axis
  size_t count() const { return size_t(nx) * size_t(ny) * size_t(nz); }
  // x fastest, so one thread's run of blocks reads whole texture rows.
  openvdb::Coord origin(size_t b) const {
    return openvdb::Coord(int(b % size_t(nx)) * kLeafDim, int(b / size_t(nx) % size_t(ny)) * kLeafDim,
                          int(b / (size_t(nx) * size_t(ny))) * kLeafDim);
  }
};

// Fills the leaf of every channel for the block at `origin`: the texel's
// value, with -0 stored as +0 (copyFromDense stores the background for any
// value equal to it). Returns, per channel, whether the block is constant
// (copyFromDense would make it a tile).
void fill_block(const Texture& tex, const openvdb::Coord& origin, float* const* out,
                char* constant) {
  const size_t nc = tex.channels.size(), w = size_t(tex.width), h = size_t(tex.height);
  const size_t x0 = size_t(origin.x()), y0 = size_t(origin.y()), z0 = size_t(origin.z());
  const float* first = tex.data.data() + ((z0 * h + y0) * w + x0) * nc;
  for (size_t c = 0; c < nc; ++c) constant[c] = 1;
  for (size_t z = 0; z < size_t(kLeafDim); ++z)
    for (size_t y = 0; y < size_t(kLeafDim); ++y) {
      const float* row = tex.data.data() + (((z0 + z) * h + y0 + y) * w + x0) * nc;
      for (size_t x = 0; x < size_t(kLeafDim); ++x)
        for (size_t c = 0; c < nc; ++c) {
          const float v = row[x * nc + c] == 0.0f ? 0.0f : row[x * nc + c];
          // Tolerance 0: LeafNode::isConstant's isApproxEqual is ==.
          const float f = first[c] == 0.0f ? 0.0f : first[c];
          constant[c] &= char(v == f);
          out[c][(x << 6) | (y << 3) | z] = v;
        }
    }
}

}  // namespace

std::vector<Tree::Ptr> direct_leaf_trees(const Texture& tex) {
  if (tex.is_array() || tex.width % kLeafDim || tex.height % kLeafDim || tex.depth % kLeafDim)
    return {};
  const size_t nc = tex.channels.size();
  const Blocks blocks{tex.width / kLeafDim, tex.height / kLeafDim, tex.depth / kLeafDim};
  const size_t n = blocks.count();
  // Block-major (block b's channels side by side); owned until a tree adopts them.
  std::vector<std::unique_ptr<Leaf>> leaves(n * nc);
  std::vector<char> constant(n * nc);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<float*> out(nc);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const openvdb::Coord origin = blocks.origin(b);
      for (size_t c = 0; c < nc; ++c) {
        // Every voxel active; the buffer left unfilled (fill_block writes it all).
        leaves[b * nc + c].reset(new Leaf(openvdb::PartialCreate(), origin, 0.0f, true));
        out[c] = leaves[b * nc + c]->buffer().data();
      }
      fill_block(tex, origin, out.data(), &constant[b * nc]);
    }
  });
  std::vector<Tree::Ptr> trees(nc);
  tbb::parallel_for(size_t(0), nc, [&](size_t c) {
    for (size_t b = 0; b < n; ++b)
      if (constant[b * nc + c]) return;  // the reference build makes this channel
    auto tree = std::make_shared<Tree>(0.0f);
    openvdb::tree::ValueAccessor<Tree> acc(*tree);
    for (size_t b = 0; b < n; ++b) acc.addLeaf(leaves[b * nc + c].release());
    trees[c] = tree;
  });
  return trees;
}

}  // namespace skybake

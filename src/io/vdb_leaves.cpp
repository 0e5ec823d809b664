#include "io/vdb_leaves.hpp"

#include <atomic>
#include <memory>
#include <vector>

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

// Fills channel c's leaf of the block at `origin`: the texel's value, with
// -0 stored as +0 (copyFromDense stores the background for any value equal
// to it). Returns whether the block is constant (copyFromDense would make it
// a tile): with tolerance 0, LeafNode::isConstant's isApproxEqual is ==.
bool fill_block(const Texture& tex, size_t c, const openvdb::Coord& origin, float* out) {
  const size_t nc = tex.channels.size(), w = size_t(tex.width), h = size_t(tex.height);
  const size_t x0 = size_t(origin.x()), y0 = size_t(origin.y()), z0 = size_t(origin.z());
  const float* texels = tex.data.data() + c;
  const float first = texels[((z0 * h + y0) * w + x0) * nc] == 0.0f ? 0.0f
                                                                      : texels[((z0 * h + y0) * w + x0) * nc];
  bool constant = true;
  for (size_t z = 0; z < size_t(kLeafDim); ++z)
    for (size_t y = 0; y < size_t(kLeafDim); ++y) {
      const float* row = texels + (((z0 + z) * h + y0 + y) * w + x0) * nc;
      for (size_t x = 0; x < size_t(kLeafDim); ++x) {
        const float v = row[x * nc] == 0.0f ? 0.0f : row[x * nc];
        constant &= v == first;
        out[(x << 6) | (y << 3) | z] = v;
      }
    }
  return constant;
}

}  // namespace

Tree::Ptr direct_leaf_tree(const Texture& tex, int c) {
  if (tex.is_array() || tex.width % kLeafDim || tex.height % kLeafDim || tex.depth % kLeafDim)
    return nullptr;
  const Blocks blocks{tex.width / kLeafDim, tex.height / kLeafDim, tex.depth / kLeafDim};
  const size_t n = blocks.count();
  // Owned until the tree adopts them; allocated here, in this thread.
  std::vector<std::unique_ptr<Leaf>> leaves(n);
  std::vector<float*> buffers(n);
  for (size_t b = 0; b < n; ++b) {
    // Every voxel active; the buffer left unfilled (fill_block writes it all).
    leaves[b].reset(new Leaf(openvdb::PartialCreate(), blocks.origin(b), 0.0f, true));
    buffers[b] = leaves[b]->buffer().data();
  }
  std::atomic<bool> constant{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b != r.end(); ++b)
      if (fill_block(tex, size_t(c), blocks.origin(b), buffers[b]))
        constant.store(true, std::memory_order_relaxed);
  });
  if (constant) return nullptr;  // the reference build makes this channel
  auto tree = std::make_shared<Tree>(0.0f);
  openvdb::tree::ValueAccessor<Tree> acc(*tree);
  for (size_t b = 0; b < n; ++b) acc.addLeaf(leaves[b].release());
  return tree;
}

}  // namespace skybake

// The VDB writer's direct leaf build (io/vdb_leaves.hpp), written one grid at
// a time (io/vdb_archive.hpp), against OpenVDB's own dense copy written by
// OpenVDB's archive writer: the files of both are byte for byte the same, and
// the grids read back by OpenVDB have the tree copyFromDense makes from the
// texture (leaves, masks, tiles and every value's bits), on shapes the direct
// build takes and shapes it hands back to the reference build.
#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "io/vdb.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

std::string tmp_path(const std::string& name, const std::string& file) {
  return skybake::test::scratch_file("io_vdb_leaves", name, file);
}

// Irregular values with exact zeros and negative zeros (stored as the
// background), in every channel.
Texture make_texture(int w, int h, int d, int channels) {
  std::vector<std::string> names;
  for (int c = 0; c < channels; ++c) names.push_back("c" + std::to_string(c));
  Texture tex(w, h, d, 1, names);
  for (size_t i = 0; i < tex.data.size(); ++i)
    tex.data[i] = i % 11 == 3   ? -0.0f
                  : i % 7 < 2   ? 0.0f
                                : float(1.5 * std::sin(0.37 * double(i) + 0.1));
  set_meta(tex.metadata, "product", "noise_shape");
  return tex;
}

// The tree OpenVDB makes of one channel: copyFromDense of an x-fastest dense
// copy, then every voxel of the box activated (vdb.hpp: dense grids).
openvdb::FloatTree::Ptr reference_tree(const Texture& tex, int c) {
  const openvdb::CoordBBox box(openvdb::Coord(0),
                               openvdb::Coord(tex.width - 1, tex.height - 1, tex.depth - 1));
  std::vector<float> plane(tex.texel_count());
  for (size_t t = 0; t < plane.size(); ++t) plane[t] = tex.data[t * tex.channels.size() + c];
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, plane.data());
  auto tree = std::make_shared<openvdb::FloatTree>(0.0f);
  openvdb::tools::copyFromDense(dense, *tree, 0.0f);
  openvdb::MaskTree mask;
  mask.fill(box, true, true);
  tree->topologyUnion(mask);
  return tree;
}

// Same nodes, tiles, masks and value bits.
void expect_same_tree(const openvdb::FloatTree& got, const openvdb::FloatTree& want,
                      const std::string& what) {
  EXPECT_EQ(got.leafCount(), want.leafCount()) << what;
  EXPECT_EQ(got.nonLeafCount(), want.nonLeafCount()) << what;
  EXPECT_EQ(got.activeTileCount(), want.activeTileCount()) << what;
  EXPECT_EQ(got.activeVoxelCount(), want.activeVoxelCount()) << what;
  for (auto it = want.cbeginLeaf(); it; ++it) {
    const auto* leaf = got.probeConstLeaf(it->origin());
    ASSERT_TRUE(leaf) << what << ": no leaf at " << it->origin();
    EXPECT_TRUE(leaf->getValueMask() == it->getValueMask()) << what << " " << it->origin();
    EXPECT_EQ(std::memcmp(leaf->buffer().data(), it->buffer().data(), it->SIZE * sizeof(float)),
              0)
        << what << ": values at " << it->origin();
  }
  for (auto it = want.cbeginValueOn(); it; ++it)
    if (it.isTileValue()) {
      float value = 1.0f;
      EXPECT_TRUE(got.probeValue(it.getCoord(), value)) << what << " tile " << it.getCoord();
      EXPECT_EQ(value, *it) << what << " tile " << it.getCoord();
    }
}

// Both builds give the same file, and OpenVDB reads back copyFromDense's trees.
void check_builds(const Texture& tex, const std::string& name,
                  VdbCompression compression = VdbCompression::none) {
  VdbWriteOptions options;
  options.compression = compression;
  options.tree_build = VdbTreeBuild::direct;
  const std::string direct = tmp_path(name, "direct.vdb");
  write_vdb(direct, tex, options);
  options.tree_build = VdbTreeBuild::dense_copy;
  const std::string dense = tmp_path(name, "dense.vdb");
  write_vdb(dense, tex, options);
  EXPECT_TRUE(skybake::test::read_file(direct) == skybake::test::read_file(dense)) << name;

  openvdb::initialize();
  openvdb::io::File file(direct);
  file.open();
  for (int c = 0; c < tex.channel_count(); ++c) {
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(tex.channels[c]));
    ASSERT_TRUE(grid) << name << " " << tex.channels[c];
    expect_same_tree(grid->tree(), *reference_tree(tex, c), name + " " + tex.channels[c]);
  }
  file.close();
}

TEST(VdbLeaves, DirectBuildIsCopyFromDenseOnWholeBlocks) {
  check_builds(make_texture(8, 8, 8, 1), "one_leaf");
  check_builds(make_texture(16, 24, 32, 4), "rgba");
  // Past one 128^3 internal node along x, and a 2D-like slab of one block.
  check_builds(make_texture(136, 8, 16, 2), "two_internal_nodes");
  check_builds(make_texture(64, 8, 8, 3), "slab");
}

// The direct build writes its grids one at a time (io/vdb_archive.hpp);
// the compression flags, restored after each grid, shape the bytes.
TEST(VdbLeaves, EveryCompressionGivesTheBytesOfOpenVdbsArchiveWriter) {
  check_builds(make_texture(16, 8, 24, 3), "blosc", VdbCompression::blosc);
  check_builds(make_texture(16, 8, 24, 3), "zip", VdbCompression::zip);
}

// OpenVDB's writer names an unnamed grid "[0]"; the one-at-a-time writer
// does not, so such a texture goes through OpenVDB's writer.
TEST(VdbLeaves, AnEmptyChannelNameIsWrittenAsOpenVdbNamesIt) {
  Texture tex = make_texture(8, 8, 16, 2);
  tex.channels = {"", "density"};
  check_builds(tex, "empty_name");
}

TEST(VdbLeaves, ShapesWithPartialBlocksTakeTheReferenceBuild) {
  check_builds(make_texture(12, 8, 8, 2), "partial_x");
  check_builds(make_texture(8, 8, 9, 1), "partial_z");
  check_builds(make_texture(16, 16, 1, 4), "2d");
}

TEST(VdbLeaves, ConstantBlocksBecomeTilesAsInTheReference) {
  Texture tex = make_texture(16, 16, 16, 3);
  // Channel 0: one block of ones (an active tile in the reference); channel
  // 1: one block of zeros and negative zeros (background); channel 2: a
  // block constant but for one value (a leaf).
  for (int z = 8; z < 16; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 8; x < 16; ++x) {
        tex.at(x, y, z, 0, 0) = 1.0f;
        tex.at(x, y, z, 0, 1) = (x + y) % 2 ? 0.0f : -0.0f;
        tex.at(x, y, z, 0, 2) = x == 9 && y == 2 && z == 11 ? 2.0f : 0.5f;
      }
  check_builds(tex, "constant_blocks");
  // Every block of a channel constant: the whole box one tile.
  Texture flat = make_texture(16, 16, 16, 2);
  for (size_t t = 0; t < flat.texel_count(); ++t) flat.data[t * 2 + 1] = 0.25f;
  check_builds(flat, "constant_channel");
}

}  // namespace
}  // namespace skybake

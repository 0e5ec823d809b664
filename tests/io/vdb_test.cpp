// Tests for io/vdb: files are read back with plain OpenVDB calls (io::File,
// grids by name, accessors, transform, metadata) that share no code with
// read_vdb, and through read_vdb. Plus determinism and refusals.
// With vdb_leaves_test.cpp, the only test files that include OpenVDB (slow
// headers).
#include "io/vdb.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "core/error.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;

std::string tmp_path(const std::string& name, const std::string& file) {
  return skybake::test::scratch_file("io_vdb", name, file);
}

// Irregular values with a run of exact zeros (density-like empty space).
Texture make_volume(int w, int h, int d) {
  Texture tex(w, h, d, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < tex.data.size(); ++i)
    tex.data[i] = i % 7 < 2 ? 0.0f : float(1.5 * std::sin(0.37 * i + 0.1));
  // One value of every metadata type, so that the round trip covers each.
  set_meta(tex.metadata, "product", "noise_shape");
  set_meta(tex.metadata, "period", 1);
  set_meta(tex.metadata, "gain", -0.20000000000000001);
  set_meta(tex.metadata, "size", glm::ivec2(5, -4));
  set_meta(tex.metadata, "box", glm::ivec3(5, 4, 3));
  set_meta(tex.metadata, "uv", glm::dvec2(0.1, 1e-300));
  set_meta(tex.metadata, "irradiance", glm::dvec3(1.0 / 3.0, 2.5, 7e10));
  return tex;
}

TEST(Vdb, GridsReadWithPlainOpenVdbMatchTheTexture) {
  const std::string path = tmp_path("plain", "t.vdb");
  const Texture tex = make_volume(5, 4, 3);
  write_vdb(path, tex, 0.25);

  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  std::vector<std::string> names;
  for (auto it = file.beginName(); it != file.endName(); ++it) names.push_back(it.gridName());
  // OpenVDB lists grids by name; the texture order is in skybake:channels.
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R"}));
  for (int c = 0; c < 4; ++c) {
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(tex.channels[c]));
    ASSERT_TRUE(grid) << tex.channels[c];
    EXPECT_EQ(grid->background(), 0.0f);
    EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(0.25));
    // Texel centres at (i + 0.5) * voxel size (docs/architecture.md "Texel centres").
    EXPECT_EQ(grid->indexToWorld(openvdb::Coord(0, 0, 0)), openvdb::Vec3d(0.125));
    EXPECT_EQ(grid->indexToWorld(openvdb::Coord(4, 3, 2)), openvdb::Vec3d(1.125, 0.875, 0.625));
    EXPECT_EQ(grid->metaValue<std::string>("skybake:product"), "noise_shape");
    // Every metadata type as OpenVDB's own typed metadata.
    EXPECT_EQ(grid->metaValue<int32_t>("skybake:period"), 1);
    EXPECT_EQ(grid->metaValue<double>("skybake:gain"), -0.20000000000000001);
    EXPECT_EQ(grid->metaValue<openvdb::Vec2i>("skybake:size"), openvdb::Vec2i(5, -4));
    EXPECT_EQ(grid->metaValue<openvdb::Vec3i>("skybake:box"), openvdb::Vec3i(5, 4, 3));
    EXPECT_EQ(grid->metaValue<openvdb::Vec2d>("skybake:uv"), openvdb::Vec2d(0.1, 1e-300));
    EXPECT_EQ(grid->metaValue<openvdb::Vec3d>("skybake:irradiance"),
              openvdb::Vec3d(1.0 / 3.0, 2.5, 7e10));
    EXPECT_EQ(grid->metaValue<std::string>("skybake:shape"), "5x4x3x1");
    EXPECT_EQ(grid->metaValue<std::string>("skybake:channels"), "R,G,B,A");
    EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(5 * 4 * 3));  // dense, zeros too
    auto acc = grid->getConstAccessor();
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) {
          const openvdb::Coord ijk(x, y, z);
          EXPECT_EQ(acc.getValue(ijk), tex.at(x, y, z, 0, c));
          EXPECT_TRUE(acc.isValueOn(ijk));
        }
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(5, 0, 0)));
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(0, 0, -1)));
  }
  file.close();
}

TEST(Vdb, ReadVdbRestoresVolumeAnd2DTextures) {
  const Texture volume = make_volume(6, 5, 4);
  Texture flat = make_volume(7, 3, 1);
  flat.channels = {"density", "temperature", "x", "a"};  // not alphabetical: file order counts
  int n = 0;
  for (const Texture* tex : {&volume, static_cast<const Texture*>(&flat)}) {
    const std::string path = tmp_path("read_vdb", std::to_string(n++) + ".vdb");
    write_vdb(path, *tex, 1.0 / tex->width);
    const Texture back = read_vdb(path);
    EXPECT_EQ(back.shape_string(), tex->shape_string());
    EXPECT_EQ(back.channels, tex->channels);
    EXPECT_EQ(back.metadata, tex->metadata);
    ASSERT_EQ(back.data.size(), tex->data.size());
    for (size_t i = 0; i < back.data.size(); ++i) ASSERT_EQ(back.data[i], tex->data[i]) << i;
  }
}

TEST(Vdb, ReadVdbTakesAForeignFileShapeFromItsActiveVoxels) {
  const std::string path = tmp_path("foreign", "t.vdb");
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(10, 20, 30), 2.0f);
  grid->tree().setValue(openvdb::Coord(12, 20, 31), 3.0f);
  openvdb::io::File(path).write({grid});
  const Texture tex = read_vdb(path);
  EXPECT_EQ(tex.shape_string(), "3x1x2");
  EXPECT_EQ(tex.channels, std::vector<std::string>{"density"});
  EXPECT_EQ(tex.at(0, 0, 0, 0, 0), 2.0f);
  EXPECT_EQ(tex.at(2, 0, 1, 0, 0), 3.0f);
  EXPECT_EQ(tex.at(1, 0, 0, 0, 0), 0.0f);
}

TEST(Vdb, SameTextureGivesIdenticalBytes) {
  const Texture tex = make_volume(9, 8, 7);
  const std::string a = tmp_path("determinism", "a.vdb"), b = tmp_path("determinism", "b.vdb");
  write_vdb(a, tex, 0.5);
  write_vdb(b, tex, 0.5);
  const std::string bytes = skybake::test::read_file(a);
  EXPECT_GT(bytes.size(), 100u);
  EXPECT_TRUE(bytes == skybake::test::read_file(b));
  // Different content, different file identity.
  Texture other = tex;
  other.data[0] += 1.0f;
  const std::string c = tmp_path("determinism", "c.vdb");
  write_vdb(c, other, 0.5);
  openvdb::io::File fa(a), fc(c);
  fa.open();
  fc.open();
  EXPECT_NE(fa.getUniqueTag(), fc.getUniqueTag());
}

TEST(Vdb, NonFiniteValuesAndArraysAreRefusedBeforeAFileExists) {
  const std::string path = tmp_path("refused", "t.vdb");
  Texture tex = make_volume(3, 3, 3);
  tex.at(1, 2, 1, 0, 3) = std::nanf("");
  EXPECT_THROW(write_vdb(path, tex, 1.0), IoError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_THROW(write_vdb(path, Texture(2, 2, 1, 3, {"R"}), 1.0), IoError);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace skybake

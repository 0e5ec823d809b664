// Small files whose headers announce gigabytes: `info` and `check-tiling`
// refuse them as file errors (exit 4) against their memory budget
// (--max-memory, default 1 GiB; io/read_budget.hpp) before allocating, and
// the readers do the same in a process whose address space would not hold
// what the header announces (a bad_alloc there is exit code 99).
#include <filesystem>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "core/error.hpp"
#include "io/dds.hpp"
#include "io/ktx2.hpp"
#include "io/read_budget.hpp"
#include "io/texture_file.hpp"
#include "support/memory_cap.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// One active voxel in a grid whose skybake:shape claims 800^3 voxels: a
// dense copy of 3.8 GiB (texture and plane) from a file of a few KB.
std::string claimed_800_cubed(const std::string& name) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(3, 4, 5), 1.0f);
  grid->insertMeta("skybake:shape", openvdb::StringMetadata("800x800x800x1"));
  const std::string path = test::scratch_file("read_budget", name, name + ".vdb");
  openvdb::io::File(path).write(openvdb::GridPtrVec{grid});
  return path;
}

// A constant zip EXR of 16384x16640 half texels, one channel: 1.02 GiB of
// float32 texels from a file of about two megabytes. Written with a row
// stride of zero, so the test never holds the image.
std::string constant_16384_wide(const std::string& name) {
  const std::string path = test::scratch_file("read_budget", name, name + ".exr");
  const int side = 16384, rows = 16640;
  Imf::Header header(side, rows);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.zipCompressionLevel() = 1;  // the fastest deflate: the test writes 512 MB of texels
  header.channels().insert("R", Imf::Channel(Imf::HALF));
  Imf::OutputFile out(path.c_str(), header);
  std::vector<half> line(side, half(0.5f));  // every row reads this one (y stride 0)
  Imf::FrameBuffer fb;
  fb.insert("R", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(line.data()), sizeof(half), 0));
  out.setFrameBuffer(fb);
  out.writePixels(rows);
  return path;
}

// The reader's answer under a cap that cannot hold what the header claims:
// 4 for an IoError, 99 for a failed allocation.
int read_within(const std::string& path, size_t headroom, uint64_t budget) {
  return test::run_with_memory_headroom(headroom, [&] {
    try {
      read_texture_file(path, budget);
    } catch (const IoError&) {
      return 4;
    }
    return 0;
  });
}

void expect_refused_by_the_commands(const std::string& path, const std::string& what) {
  for (const char* command : {"info", "check-tiling"}) {
    SCOPED_TRACE(command);
    const auto r = test::run_skybake({command, path});
    EXPECT_EQ(r.exit_code, 4) << r.err;
    EXPECT_THAT(r.err, HasSubstr(path + ": reading it takes "));
    EXPECT_THAT(r.err, HasSubstr(what));
    EXPECT_THAT(r.err, HasSubstr("more than the memory budget of 1 GiB; raise --max-memory"));
  }
}

TEST(ReadBudget, VdbClaimingAGiantShapeIsRefusedBeforeTheDenseCopy) {
  const std::string path = claimed_800_cubed("vdb_800");
  EXPECT_LT(fs::file_size(path), 100000u);
  expect_refused_by_the_commands(path, "a dense 800x800x800 copy of 1 float grid and one plane");
  EXPECT_EQ(read_within(path, size_t(768) << 20, kDefaultReadBudget), 4);
}

TEST(ReadBudget, ZipExrOfOverAGibibyteIsRefusedBeforeThePixels) {
  const std::string path = constant_16384_wide("exr_16384");
  EXPECT_LT(fs::file_size(path), uint64_t(4) << 20);
  expect_refused_by_the_commands(path, "(16384x16640x1x1 float32 texels with 1 channel)");
  EXPECT_EQ(read_within(path, size_t(768) << 20, kDefaultReadBudget), 4);
}

// DDS and KTX2 hold their texels, so only a small budget refuses them:
// a 256x256 RGBA float32 level is 1 MiB decoded and 1 MiB of file.
TEST(ReadBudget, MaxMemorySetsTheBudgetForEveryFormat) {
  Texture tex(256, 256, 1, 1, {"R", "G", "B", "A"});
  const std::string dds = test::scratch_file("read_budget", "small", "small.dds");
  const std::string ktx2 = test::scratch_file("read_budget", "small", "small.ktx2");
  write_dds(dds, {tex}, DdsFormat::R32G32B32A32_FLOAT);
  write_ktx2(ktx2, {tex}, Ktx2Format::R32G32B32A32_SFLOAT);
  for (const std::string& path : {dds, ktx2}) {
    SCOPED_TRACE(path);
    const auto fits = test::run_skybake({"info", path});
    EXPECT_EQ(fits.exit_code, 0) << fits.err;
    const auto refused = test::run_skybake({"info", "--max-memory", "1M", path});
    EXPECT_EQ(refused.exit_code, 4) << refused.err;
    EXPECT_THAT(refused.err, HasSubstr("more than the memory budget of 1 MiB"));
    const auto tiling = test::run_skybake({"check-tiling", path, "--max-memory", "3M"});
    EXPECT_NE(tiling.exit_code, 4) << tiling.err;
  }
  const auto bad = test::run_skybake({"info", "--max-memory", "lots", dds});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
}

}  // namespace
}  // namespace skybake

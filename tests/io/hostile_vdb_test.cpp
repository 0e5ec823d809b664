// Corrupted and hostile VDB files: the layout walk (io/vdb_layout.hpp)
// refuses every length that does not fit before OpenVDB allocates it, and
// read_vdb bounds the dense copy. A sweep of mutated files must end in a
// texture or an IoError, with the process's memory staying small.
#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "core/error.hpp"
#include "io/vdb.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::vector<char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::vector<char>& b) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
}

// A small genuine file: 8x8x8 with two channels.
std::string genuine(const std::string& name) {
  Texture tex(8, 8, 8, 1, {"R", "G"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(i % 13) / 13.0f;
  const std::string path = test::scratch_file("hostile_vdb", name, name + ".vdb");
  write_vdb(path, tex, 1.0);
  return path;
}

std::string refusal(const std::string& path) {
  try {
    read_vdb(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

// The offset of the first blosc chunk: an int64 size followed by a blosc
// header (version 2) whose compressed size is that size.
size_t first_blosc_chunk(const std::vector<char>& b) {
  for (size_t k = 0; k + 24 <= b.size(); ++k) {
    int64_t n;
    uint32_t cbytes;
    std::memcpy(&n, &b[k], 8);
    std::memcpy(&cbytes, &b[k + 20], 4);
    if (n >= 16 && n < 100000 && b[k + 8] == 2 && int64_t(cbytes) == n) return k;
  }
  ADD_FAILURE() << "no blosc chunk found";
  return 0;
}

TEST(HostileVdb, CompressedChunkSizesAreCheckedAgainstTheFile) {
  const std::string path = genuine("chunk");
  const std::vector<char> good = bytes_of(path);
  const size_t at = first_blosc_chunk(good);
  for (const int64_t n : {int64_t(1) << 40, -(int64_t(1) << 40), int64_t(17)}) {
    std::vector<char> b = good;
    std::memcpy(&b[at], &n, 8);
    write_bytes(path, b);
    const std::string why = refusal(path);
    EXPECT_THAT(why, HasSubstr(path + ": not a VDB skybake can read safely: ")) << n;
  }
  std::vector<char> b = good;
  const uint32_t huge = 0x7fffffff;
  std::memcpy(&b[at + 8 + 4], &huge, 4);  // the blosc header's uncompressed size
  write_bytes(path, b);
  EXPECT_THAT(refusal(path), HasSubstr("blosc header"));
}

TEST(HostileVdb, MetadataLengthsAreCheckedAgainstTheFile) {
  const std::string path = genuine("metadata");
  std::vector<char> b = bytes_of(path);
  const std::string key = "skybake:shape";
  const auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
  ASSERT_NE(it, b.end());
  const uint32_t huge = 0x7fffffff;
  std::memcpy(&*(it - 4), &huge, 4);
  write_bytes(path, b);
  EXPECT_THAT(refusal(path), HasSubstr("metadata name needs 2147483647 bytes"));
}

TEST(HostileVdb, AUuidWithWhiteSpaceIsRefused) {
  // OpenVDB reads the UUID with >>, skipping white space: a line break in it
  // would shift OpenVDB past this walk, onto an unchecked length (a fuzzer
  // input made it allocate 4 GB for a grid's instance parent name).
  const std::string path = genuine("uuid");
  const std::vector<char> good = bytes_of(path);
  constexpr size_t kUuidAt = 8 + 4 + 8 + 1;  // magic, version, library version, offsets flag
  for (const char c : {'\r', ' ', 'g'}) {
    std::vector<char> b = good;
    b[kUuidAt + 25] = c;
    write_bytes(path, b);
    EXPECT_THAT(refusal(path), HasSubstr("expected a UUID of 32 hex digits and 4 hyphens")) << int(c);
  }
  write_bytes(path, good);
  EXPECT_NO_THROW(read_vdb(path));
}

TEST(HostileVdb, TruncatedFilesAreRefused) {
  const std::string path = genuine("truncated");
  const std::vector<char> good = bytes_of(path);
  for (const size_t size : {size_t(0), size_t(40), size_t(100), size_t(500), size_t(2000),
                            good.size() / 2, good.size() - 1}) {
    write_bytes(path, std::vector<char>(good.begin(), good.begin() + long(size)));
    EXPECT_THAT(refusal(path), HasSubstr(path)) << size;
  }
}

// 2000 files with 1 to 4 bytes changed (half of them in the first 1500
// bytes, where the header, metadata and topology are), some truncated.
TEST(HostileVdb, MutatedFilesEndInATextureOrAFileErrorWithinBoundedMemory) {
  const std::string path = genuine("mutated");
  const std::vector<char> good = bytes_of(path);
  std::mt19937 rng(1234);
  const auto below = [&](size_t n) { return size_t(rng() % n); };
  const char values[] = {0, char(0xff), 0x7f, char(0x80)};
  int read = 0, refused = 0;
  for (int i = 0; i < 2000; ++i) {
    std::vector<char> b = good;
    for (size_t k = 0, n = 1 + below(4); k < n; ++k) {
      const size_t at = below(2) ? below(b.size()) : below(std::min<size_t>(b.size(), 1500));
      b[at] = below(2) ? values[below(4)] : char(below(256));
    }
    if (below(4) == 0) b.resize(below(b.size()));
    write_bytes(path, b);
    try {
      read_vdb(path);
      ++read;
    } catch (const IoError&) {
      ++refused;
    }
  }
  EXPECT_EQ(read + refused, 2000);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  EXPECT_LT(usage.ru_maxrss, 1L << 20) << "peak resident set in KiB";
}

TEST(HostileVdb, HugeActiveRegionIsRefusedBeforeTheDenseCopy) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  // Root tiles only (4096-aligned): cheap in memory, 102400^3 active voxels.
  grid->tree().sparseFill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(25 * 4096 - 1)),
                          1.0f, true);
  const std::string path = test::scratch_file("hostile_vdb", "huge_region", "huge_region.vdb");
  openvdb::io::File(path).write(openvdb::GridPtrVec{grid});
  EXPECT_THAT(refusal(path), HasSubstr("a dense copy of 1073741824000000 voxels x 1 grids is "
                                       "over the 4 GiB limit"));
  auto far = openvdb::FloatGrid::create(0.0f);
  far->tree().sparseFill(openvdb::CoordBBox(openvdb::Coord((1 << 30) + 8192),
                                            openvdb::Coord((1 << 30) + 8192 + 4095)),
                         1.0f, true);
  openvdb::io::File(path).write(openvdb::GridPtrVec{far});
  EXPECT_THAT(refusal(path), HasSubstr("coordinate 1073750016 outside +-2^30"));
}

TEST(HostileVdb, RepeatedChannelNamesAreRefused) {
  Texture tex(2, 2, 2, 1, {"R"});
  const std::string path = test::scratch_file("hostile_vdb", "channels", "channels.vdb");
  write_vdb(path, tex, 1.0);
  openvdb::initialize();
  openvdb::io::File in(path);
  in.open();
  auto grids = in.getGrids();
  in.close();
  (*grids)[0]->insertMeta("skybake:channels", openvdb::StringMetadata("R,R,R,R"));
  openvdb::io::File(path).write(*grids);
  EXPECT_THAT(refusal(path), HasSubstr("expected distinct grids in skybake:channels, got 'R'"));
}

// Files from other writers: every compression OpenVDB has, half or float
// values, sparse activity (so inactive-value flags and selection masks
// occur), tiles at the root.
TEST(HostileVdb, ForeignCompressionsAndHalfStillRead) {
  openvdb::initialize();
  const std::string path = test::scratch_file("hostile_vdb", "foreign", "foreign.vdb");
  using namespace openvdb::io;
  for (const uint32_t compression : std::vector<uint32_t>{
           COMPRESS_NONE, COMPRESS_ZIP, COMPRESS_ZIP | COMPRESS_ACTIVE_MASK,
           COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK}) {
    for (const bool half : {false, true}) {
      auto grid = openvdb::FloatGrid::create(0.25f);
      grid->setName("density");
      auto acc = grid->getAccessor();
      for (int i = 0; i < 300; ++i) acc.setValue(openvdb::Coord(i % 37, i % 11, i % 23), i * 0.5f);
      acc.setValueOff(openvdb::Coord(40, 2, 2), -3.0f);
      grid->tree().sparseFill(openvdb::CoordBBox(openvdb::Coord(4096), openvdb::Coord(8191)),
                              2.0f, false);
      grid->setSaveFloatAsHalf(half);
      openvdb::io::File file(path);
      file.setCompression(compression);
      file.write(openvdb::GridPtrVec{grid});
      EXPECT_EQ(refusal(path), "") << compression << " half " << half;
    }
  }
}

TEST(HostileVdb, AFifoIsRefusedWithoutBlocking) {
  const std::string path = test::scratch_file("hostile_vdb", "fifo", "fifo.vdb");
  ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
  EXPECT_THAT(refusal(path), HasSubstr(path + ": expected a regular file"));
  const auto r = test::run_skybake({"info", path});
  EXPECT_EQ(r.exit_code, 4) << r.err;
}

}  // namespace
}  // namespace skybake

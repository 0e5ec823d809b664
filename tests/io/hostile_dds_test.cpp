// DDS headers that announce more than a reader should allocate: each size
// field is bounded and named in the refusal, before anything is allocated
// (sparse files stand in for huge ones, so nothing big is written).
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/dds.hpp"
#include "support/memory_cap.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct Fields {
  uint32_t width = 1, height = 1, depth = 0, mips = 1, dimension = 3, array_size = 1;
  DdsFormat format = DdsFormat::R8_UNORM;
  uint64_t data_bytes = 1;  // bytes after the 148-byte header (sparse)
};

// A header written by write_dds, its size fields then overwritten.
std::string forged(const std::string& name, const Fields& f) {
  const std::string path = test::scratch_file("hostile_dds", name, name + ".dds");
  write_dds(path, {Texture(1, 1, 1, 1, {"R"})}, DdsFormat::R8_UNORM);
  std::vector<char> b(dds::kHeaderBytes);
  std::ifstream(path, std::ios::binary).read(b.data(), std::streamsize(b.size()));
  const auto put = [&](size_t at, uint32_t v) { std::memcpy(&b[at], &v, 4); };
  put(12, f.height);
  put(16, f.width);
  put(24, f.depth);
  put(28, f.mips);
  put(128, uint32_t(f.format));
  put(132, f.dimension);
  put(140, f.array_size);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
  fs::resize_file(path, dds::kHeaderBytes + f.data_bytes);
  return path;
}

std::string refusal(const std::string& path) {
  try {
    read_dds(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileDds, QuarterBillionLayersOfOneTexelAreRefusedByArraySize) {
  Fields f;
  f.array_size = 268435456;
  f.format = DdsFormat::R32G32B32A32_FLOAT;
  f.data_bytes = uint64_t(f.array_size) * 16;  // 4.3 GB, sparse: the header matches the length
  const std::string path = forged("layers", f);
  // Refused before allocating: the same read with 64 MiB to spare (the
  // layers would take 4.3 GB) still ends in the refusal.
  const std::string expected = path + ": expected arraySize from 1 to 2048, got 268435456";
  EXPECT_EQ(test::run_with_memory_headroom(
                64 << 20, [&] { return refusal(path).find(expected) != std::string::npos ? 0 : 1; }),
            0);
  EXPECT_THAT(refusal(path), HasSubstr(expected));
  const auto r = test::run_skybake({"info", path});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_THAT(r.err, HasSubstr("arraySize"));
}

TEST(HostileDds, EachSizeFieldIsBoundedAndNamed) {
  Fields wide;
  wide.width = 20000;
  EXPECT_THAT(refusal(forged("width", wide)),
              HasSubstr("expected width from 1 to 16384 for a 2D texture, got 20000"));
  Fields tall;
  tall.height = 0;
  EXPECT_THAT(refusal(forged("height", tall)),
              HasSubstr("expected height from 1 to 16384 for a 2D texture, got 0"));
  Fields deep;
  deep.dimension = 4;
  deep.depth = 4096;
  EXPECT_THAT(refusal(forged("depth", deep)),
              HasSubstr("expected depth from 1 to 2048 for a volume, got 4096"));
  Fields volume_array;
  volume_array.dimension = 4;
  volume_array.depth = 2;
  volume_array.array_size = 2;
  EXPECT_THAT(refusal(forged("volume_array", volume_array)),
              HasSubstr("expected arraySize 1 for a volume, got 2"));
  Fields mips;
  mips.mips = 40;
  EXPECT_THAT(refusal(forged("mips", mips)),
              HasSubstr("expected mipMapCount at most 1 for 1x1x1, got 40"));
}

TEST(HostileDds, DecodedSizeIsCappedEvenWhenTheFileIsThatLong) {
  Fields f;
  f.width = f.height = 16384;
  f.array_size = 2048;
  f.format = DdsFormat::R8G8B8A8_UNORM;
  f.data_bytes = uint64_t(16384) * 16384 * 4 * 2048;  // 2 TiB, sparse
  std::string why;
  try {
    why = refusal(forged("decoded", f));
  } catch (const fs::filesystem_error& e) {
    GTEST_SKIP() << "the file system has no 2 TiB sparse files: " << e.what();
  }
  EXPECT_THAT(why, HasSubstr("expected at most 4 GiB of float32 texels (all mip levels and "
                             "layers), got 8796093022208 bytes for 16384x16384x1 with "
                             "arraySize 2048 and 1 mip levels"));
}

TEST(HostileDds, AFifoIsRefusedWithoutBlocking) {
  const std::string path = test::scratch_file("hostile_dds", "fifo", "fifo.dds");
  ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
  EXPECT_THAT(refusal(path), HasSubstr(path + ": expected a regular file"));
}

TEST(HostileDds, GenuineFilesStillRead) {
  Texture t(4, 2, 1, 3, {"R", "G"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i % 7) / 7.0f;
  const std::string path = test::scratch_file("hostile_dds", "genuine", "genuine.dds");
  write_dds(path, {t}, DdsFormat::R32G32B32A32_FLOAT);
  const DdsImage back = read_dds(path);
  ASSERT_EQ(back.mips.size(), 1u);
  EXPECT_EQ(back.mips[0].shape_string(), "4x2[3]");
}

}  // namespace
}  // namespace skybake

namespace skybake {
namespace {

// The check above can fail: a read that allocated what the header claims
// would end the child with 99, as this allocation does.
TEST(MemoryHeadroom, AnAllocationBeyondItFails) {
  EXPECT_EQ(test::run_with_memory_headroom(64 << 20,
                                           [] {
                                             std::vector<char> big(size_t(512) << 20, 1);
                                             return big[12345] == 1 ? 0 : 2;
                                           }),
            99);
  EXPECT_EQ(test::run_with_memory_headroom(64 << 20, [] { return 0; }), 0);
}

}  // namespace
}  // namespace skybake

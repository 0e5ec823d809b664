// BufferedOutFile (io/buffered_out_file.hpp) against std::ofstream: the same
// writes, tellp and seeks give the same bytes, across buffer boundaries.
#include "io/buffered_out_file.hpp"

#include <fstream>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

// Pieces of 1 to 3000 bytes, a position noted, patched later, as OpenVDB
// does with its stream offsets; returns the positions tellp gave.
std::vector<long long> write_pattern(std::ostream& os) {
  std::vector<long long> told;
  std::string piece;
  for (int i = 0; i < 200; ++i) {
    piece.assign(size_t(1 + (i * 977) % 3000), char('a' + i % 26));
    if (i % 17 == 0) {
      told.push_back(static_cast<long long>(os.tellp()));
      os.write("--------", 8);  // patched below
    }
    os.write(piece.data(), std::streamsize(piece.size()));
    os.put(char(i));
  }
  const auto end = os.tellp();
  for (size_t k = 0; k < told.size(); ++k) {
    os.seekp(told[k]);
    const std::string patch = "patch" + std::to_string(k % 10) + "..";
    os.write(patch.data(), 8);
  }
  os.seekp(end);
  os.write("tail", 4);
  told.push_back(static_cast<long long>(os.tellp()));
  return told;
}

TEST(BufferedOutFile, GivesTheBytesOfAnOfstream) {
  const std::string want_path = test::scratch_file("io_buffered", "same", "want.bin");
  std::vector<long long> want_told;
  {
    std::ofstream want(want_path, std::ios::binary | std::ios::trunc);
    want_told = write_pattern(want);
  }
  for (size_t buffer : {size_t(7), size_t(4096), size_t(1) << 20}) {
    const std::string path = test::scratch_file("io_buffered", "same", std::to_string(buffer));
    BufferedOutFile out(path, buffer);
    std::ostream os(&out);
    EXPECT_EQ(write_pattern(os), want_told) << buffer;
    EXPECT_TRUE(os.good()) << buffer;
    out.close();
    EXPECT_TRUE(test::read_file(path) == test::read_file(want_path)) << buffer;
  }
}

TEST(BufferedOutFile, AnUnwritablePathIsAnIoError) {
  EXPECT_THROW(BufferedOutFile("/nonexistent-folder/x.bin"), IoError);
}

}  // namespace
}  // namespace skybake

// io/texel_spill.hpp: texels put aside come back bit for bit, the buffer is
// released meanwhile, the file has no name in the folder, and without a
// usable folder the texels simply stay.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/texel_spill.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

Texture numbered(int w, int h, int d) {
  Texture t(w, h, d, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i) * 0.5f - 7.25f;
  return t;
}

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.exists() ? 1 : 0;
  return n;
}

TEST(TexelSpill, TexelsComeBackBitForBitAndLeaveMemoryMeanwhile) {
  const fs::path dir = test::test_dir("texel_spill");
  TexelSpill spill(dir);
  Texture a = numbered(64, 32, 8), b = numbered(3, 5, 1);  // one mapped, one small buffer
  const Texture a0 = a, b0 = b;
  for (int round = 0; round < 3; ++round) {
    spill.put(7, a);
    spill.put(2, b);
    EXPECT_TRUE(a.data.empty());
    EXPECT_TRUE(b.data.empty());
    EXPECT_EQ(a.width, 64);  // the shape stays
    EXPECT_EQ(entries(dir), 0u) << "the file has no name";
    spill.take(7, a);
    spill.take(2, b);
    ASSERT_EQ(a.data, a0.data);
    ASSERT_EQ(b.data, b0.data);
    for (float& v : a.data) v += 1.0f;  // a new running sum each round
    spill.put(7, a);
    spill.take(7, a);
    for (float& v : a.data) v -= 1.0f;
  }
  // Taking what is not out changes nothing.
  spill.take(7, a);
  spill.take(99, a);
  EXPECT_EQ(a.data, a0.data);
}

TEST(TexelSpill, WithoutAFolderTheTexelsStay) {
  for (const fs::path& folder : {fs::path(), test::test_dir("texel_spill") / "missing"}) {
    TexelSpill spill(folder);
    Texture a = numbered(64, 32, 8);
    const Texture a0 = a;
    spill.put(0, a);
    EXPECT_EQ(a.data, a0.data) << folder;
    spill.take(0, a);
    EXPECT_EQ(a.data, a0.data) << folder;
  }
}

}  // namespace
}  // namespace skybake

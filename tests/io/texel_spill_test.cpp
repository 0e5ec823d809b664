// io/texel_spill.hpp: sums put aside come back bit for bit, added to the
// texels given, the buffer released meanwhile and the file nameless in the
// folder; without a usable folder the sums are held in memory, with the
// same results.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/texel_spill.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

Texture numbered(int w, int h, int d, float scale) {
  Texture t(w, h, d, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = (float(i) * 0.5f - 7.25f) * scale;
  return t;
}

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.exists() ? 1 : 0;
  return n;
}

// Three rounds of sum = share + sum for a mapped and a small texture.
void run_sums(TexelSpill& spill, bool on_disk, const fs::path& dir) {
  Texture sum_a = numbered(64, 32, 8, 1.0f), sum_b = numbered(3, 5, 1, 1.0f);
  TexelVector want_a = sum_a.data, want_b = sum_b.data;
  spill.put(7, sum_a);
  spill.put(2, sum_b);
  for (int round = 1; round <= 3; ++round) {
    EXPECT_TRUE(sum_a.data.empty());
    EXPECT_TRUE(sum_b.data.empty());
    EXPECT_EQ(sum_a.width, 64);  // the shape stays
    if (on_disk) EXPECT_EQ(entries(dir), 0u) << "the file has no name";
    Texture a = numbered(64, 32, 8, 0.1f * round), b = numbered(3, 5, 1, -0.3f * round);
    for (size_t i = 0; i < want_a.size(); ++i) want_a[i] = a.data[i] + want_a[i];
    for (size_t i = 0; i < want_b.size(); ++i) want_b[i] = b.data[i] + want_b[i];
    spill.add_to(7, a);
    spill.add_to(2, b);
    ASSERT_EQ(a.data, want_a);
    ASSERT_EQ(b.data, want_b);
    // Taken: a second add changes nothing.
    spill.add_to(7, a);
    ASSERT_EQ(a.data, want_a);
    sum_a = std::move(a);
    sum_b = std::move(b);
    spill.put(7, sum_a);
    spill.put(2, sum_b);
  }
}

TEST(TexelSpill, SumsComeBackBitForBitFromANamelessFile) {
  const fs::path dir = test::test_dir("texel_spill");
  TexelSpill spill(dir);
  run_sums(spill, true, dir);
}

TEST(TexelSpill, WithoutAFolderTheSumsAreHeldInMemory) {
  for (const fs::path& folder : {fs::path(), test::test_dir("texel_spill") / "missing"}) {
    TexelSpill spill(folder);
    run_sums(spill, false, folder);
  }
}

TEST(TexelSpill, NothingKeptAddsNothing) {
  TexelSpill spill(test::test_dir("texel_spill"));
  Texture a = numbered(8, 8, 1, 1.0f);
  const TexelVector before = a.data;
  spill.add_to(3, a);
  EXPECT_EQ(a.data, before);
}

}  // namespace
}  // namespace skybake

// populate_pages faults pages in without changing what they hold, on any
// range (unaligned, shorter than a page, empty), and a Texture, whose large
// buffers go through it, is all zeros however many threads and whatever
// the allocator hands back (a freed texture's dirty memory included). The
// texels' allocator aligns huge buffers and keeps a vector's values.
#include <gtest/gtest.h>

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

#include <tbb/global_control.h>

#include "core/fresh_pages.hpp"
#include "core/texture.hpp"

namespace skybake {
namespace {

std::vector<unsigned char> pattern(size_t n) {
  std::vector<unsigned char> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<unsigned char>((i * 131 + 7) % 251 + 1);
  return v;
}

TEST(PopulatePages, KeepsTheContentsOfAnyRange) {
  const std::vector<unsigned char> want = pattern((size_t(3) << 20) + 123);
  for (size_t threads : {1u, 2u}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<unsigned char> v = want;
    populate_pages(v.data(), v.size());
    populate_pages(v.data() + 1000, (size_t(2) << 20) + 77);  // unaligned both ends
    populate_pages(v.data() + 5, 100);                        // inside one page
    populate_pages(v.data() + 4096, 0);
    EXPECT_TRUE(v == want) << threads << " threads";
  }
}

TEST(PopulatePages, FreshMemoryReadsZeroAndTakesWrites) {
  const size_t bytes = size_t(2) << 20;
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(p, MAP_FAILED);
  auto* b = static_cast<unsigned char*>(p);
  populate_pages(b, bytes);
  EXPECT_TRUE(std::all_of(b, b + bytes, [](unsigned char c) { return c == 0; }));
  b[0] = 1;
  b[bytes - 1] = 2;
  EXPECT_EQ(b[0] + b[bytes - 1], 3);
  munmap(p, bytes);
}

bool all_zero(const Texture& t) {
  return std::all_of(t.data.begin(), t.data.end(), [](float v) { return v == 0.0f; });
}

TEST(Texture, LargeAndSmallTexturesStartAtZero) {
  for (size_t threads : {1u, 2u}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    // 3.4 MB, not a whole number of pages; then a small one.
    const Texture big(129, 67, 33, 1, {"R", "G", "B"});
    ASSERT_GE(big.data.size() * sizeof(float), kPopulateMinBytes);
    EXPECT_EQ(big.data.size(), size_t(129) * 67 * 33 * 3);
    EXPECT_TRUE(all_zero(big)) << threads << " threads";
    const Texture small(16, 16, 1, 2, {"R"});
    EXPECT_EQ(small.data.size(), size_t(16) * 16 * 2);
    EXPECT_TRUE(all_zero(small));
  }
}

TEST(Texture, StartsAtZeroInMemoryAnotherTextureWrote) {
  for (int round = 0; round < 3; ++round) {
    {
      Texture dirty(96, 96, 96, 1, {"R"});
      std::fill(dirty.data.begin(), dirty.data.end(), 1.0f);
    }
    const Texture fresh(96, 96, 96, 1, {"R"});
    EXPECT_TRUE(all_zero(fresh)) << round;
  }
}

TEST(FreshPagesAllocator, ValueInitializedVectorsAreZeroInMemoryAnotherOneWrote) {
  // Either side of the mapping threshold, and a size that is not a whole
  // number of huge pages: the elements a value-initialization leaves as the
  // allocator gave them must be 0.0f, also where a freed vector was dirty.
  for (size_t n : {size_t(1000), kPopulateMinBytes / sizeof(float) - 1,
                   kPopulateMinBytes / sizeof(float), (size_t(5) << 20) / sizeof(float) + 3}) {
    for (int round = 0; round < 3; ++round) {
      {
        TexelVector dirty(n);
        std::fill(dirty.begin(), dirty.end(), -7.0f);
      }
      const TexelVector fresh(n);
      ASSERT_EQ(fresh.size(), n);
      EXPECT_TRUE(std::all_of(fresh.begin(), fresh.end(), [](float v) { return v == 0.0f; }))
          << n << " floats, round " << round;
      TexelVector grown;
      grown.resize(n);
      EXPECT_TRUE(std::all_of(grown.begin(), grown.end(), [](float v) { return v == 0.0f; }));
    }
  }
}

TEST(FreshPagesAllocator, HugePageBuffersStartOnAHugePageBoundary) {
  const size_t huge = size_t(2) << 20;
  for (size_t bytes : {huge, (size_t(5) << 20) + 12, size_t(33) << 20}) {
    void* p = allocate_fresh_pages(bytes);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % huge, 0u) << bytes;
    auto* b = static_cast<unsigned char*>(p);
    b[0] = 1;
    b[bytes - 1] = 2;  // the whole size is writable
    EXPECT_EQ(b[0] + b[bytes - 1], 3);
    free_fresh_pages(p, bytes);
  }
  // Below the populate threshold: calloc, any alignment it gives.
  void* small = allocate_fresh_pages(100);
  ASSERT_NE(small, nullptr);
  free_fresh_pages(small, 100);
}

TEST(FreshPagesAllocator, AVectorKeepsItsValuesAcrossEveryKindOfBuffer) {
  // Growth moves the values from plain new to populated to huge-page
  // buffers; a copy and a comparison go through the allocator too.
  TexelVector v;
  for (size_t i = 0; i < (size_t(3) << 20); ++i) v.push_back(float(i % 1000));
  bool same = true;
  for (size_t i = 0; i < v.size(); ++i) same = same && v[i] == float(i % 1000);
  EXPECT_TRUE(same);
  const TexelVector copy = v;
  EXPECT_TRUE(copy == v);
  EXPECT_TRUE(FreshPagesAllocator<float>() == FreshPagesAllocator<double>());
}

TEST(FreshPagesAllocator, RefusesASizeThatOverflows) {
  FreshPagesAllocator<float> a;
  EXPECT_THROW((void)a.allocate(size_t(-1) / 2), std::bad_alloc);
}

}  // namespace
}  // namespace skybake

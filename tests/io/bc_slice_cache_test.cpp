// BcSliceCache (io/block_compression.hpp): the DDS and KTX2 files of one
// output share one encoding of every block-compressed slice, and the files
// are the bytes each writer makes on its own.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "io/dds.hpp"
#include "io/ktx2.hpp"
#include "support/file_bytes.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

Texture smooth_volume(int n, int channels) {
  const std::vector<std::string> names = {"R", "G", "B", "A"};
  Texture t(n, n, n, 1, {names.begin(), names.begin() + channels});
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < channels; ++c)
          t.texel(x, y, z)[c] = 0.5f + 0.45f * std::sin(0.37f * x + 0.23f * y * (c + 1) + 0.51f * z);
  return t;
}

TEST(BcSliceCache, EncodesASliceOnceAndGivesEncodeBcsBytes) {
  const Texture t = smooth_volume(8, 4);
  BcSliceCache cache;
  const std::vector<uint8_t>& a = cache.encode(t.texel(0, 0, 1), 8, 8, 4, BcFormat::bc3);
  const std::vector<uint8_t>& b = cache.encode(t.texel(0, 0, 1), 8, 8, 4, BcFormat::bc3);
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(cache.encoded(), 1u);
  EXPECT_EQ(a, encode_bc(t.texel(0, 0, 1), 8, 8, 4, BcFormat::bc3));
  // Another slice, format or channel count is another entry.
  cache.encode(t.texel(0, 0, 2), 8, 8, 4, BcFormat::bc3);
  cache.encode(t.texel(0, 0, 1), 8, 8, 3, BcFormat::bc1);
  EXPECT_EQ(cache.encoded(), 3u);
}

TEST(BcSliceCache, DdsAndKtx2OfOneChainEncodeEachSliceOnceWithTheSameBytes) {
  const Texture top = smooth_volume(8, 4);
  const std::vector<Texture> lower = build_lower_mips(top, MipEdge::wrap);
  MipLevels levels{&top};
  size_t slices = size_t(top.depth);
  for (const Texture& l : lower) levels.push_back(&l), slices += size_t(l.depth);
  const std::string dir = test::test_dir("bc_slice_cache").string();

  BcSliceCache cache;
  write_dds(dir + "/shared.dds", levels, DdsFormat::BC3_UNORM, DdsHeader::dx10, FiniteCheck::run,
            &cache);
  EXPECT_EQ(cache.encoded(), slices);  // 8 + 4 + 2 + 1 slices of the chain
  write_ktx2(dir + "/shared.ktx2", levels, Ktx2Format::BC3_UNORM_BLOCK, FiniteCheck::run, &cache);
  EXPECT_EQ(cache.encoded(), slices) << "the KTX2 file encoded slices again";

  write_dds(dir + "/alone.dds", levels, DdsFormat::BC3_UNORM);
  write_ktx2(dir + "/alone.ktx2", levels, Ktx2Format::BC3_UNORM_BLOCK);
  EXPECT_EQ(test::read_bytes(dir + "/shared.dds"), test::read_bytes(dir + "/alone.dds"));
  EXPECT_EQ(test::read_bytes(dir + "/shared.ktx2"), test::read_bytes(dir + "/alone.ktx2"));
}

}  // namespace
}  // namespace skybake

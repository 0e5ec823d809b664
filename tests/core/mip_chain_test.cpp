// Tests for core/mip_chain.hpp: level sizes (halve each axis, floor, min 1),
// the area-weighted box filter on hand-computed cases, mean preservation,
// constants, tiling of periodic textures at every level, 3D and arrays, and
// the same bits for 1 and 2 threads.
#include "core/mip_chain.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/math.hpp"

namespace skybake {
namespace {

double channel_mean(const Texture& t, int layer, int c) {
  double sum = 0;
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) sum += t.at(x, y, z, layer, c);
  return sum / (double(t.width) * t.height * t.depth);
}

TEST(MipCount, FullChainLength) {
  EXPECT_EQ(mip_count(1, 1, 1), 1);
  EXPECT_EQ(mip_count(2, 1, 1), 2);
  EXPECT_EQ(mip_count(256, 64, 1), 9);  // 256 = 2^8
  EXPECT_EQ(mip_count(255, 3, 1), 8);   // floor(log2 255) = 7
  EXPECT_EQ(mip_count(4, 4, 32), 6);
  EXPECT_EQ(mip_count(5, 3), 3);
}

TEST(MipChain, LevelSizesHalveEachAxisWithFloorAndMinimumOne) {
  const Texture t(12, 5, 3, 1, {"R"});
  const auto chain = build_mip_chain(t, MipEdge::wrap);
  const int expected[][3] = {{12, 5, 3}, {6, 2, 1}, {3, 1, 1}, {1, 1, 1}};
  ASSERT_EQ(chain.size(), 4u);
  for (size_t i = 0; i < chain.size(); ++i) {
    EXPECT_EQ(chain[i].width, expected[i][0]) << i;
    EXPECT_EQ(chain[i].height, expected[i][1]) << i;
    EXPECT_EQ(chain[i].depth, expected[i][2]) << i;
    EXPECT_EQ(chain[i].layers, 1);
    EXPECT_EQ(chain[i].data.size(), chain[i].texel_count());
  }
}

TEST(MipChain, EvenSizesAverageTwoByTwo) {
  Texture t(4, 2, 1, 1, {"R", "G"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      t.at(x, y, 0, 0, 0) = float(x + 4 * y);
      t.at(x, y, 0, 0, 1) = float(x * x);
    }
  const auto chain = build_mip_chain(t, MipEdge::clamp);
  ASSERT_EQ(chain.size(), 3u);
  // Level 1 (2x1): texel 0 averages (0,1,4,5), texel 1 averages (2,3,6,7).
  EXPECT_FLOAT_EQ(chain[1].at(0, 0, 0, 0, 0), 2.5f);
  EXPECT_FLOAT_EQ(chain[1].at(1, 0, 0, 0, 0), 4.5f);
  EXPECT_FLOAT_EQ(chain[1].at(0, 0, 0, 0, 1), 0.5f);  // (0 + 1) / 2
  EXPECT_FLOAT_EQ(chain[1].at(1, 0, 0, 0, 1), 6.5f);  // (4 + 9) / 2
  EXPECT_FLOAT_EQ(chain[2].at(0, 0, 0, 0, 0), 3.5f);
}

TEST(MipChain, OddSizesWeightTexelsByOverlap) {
  // 5 -> 2: output 0 covers [0, 2.5) and output 1 covers [2.5, 5) in texel
  // units, so texel 2 counts half in each.
  Texture t(5, 1, 1, 1, {"R"});
  const float v[5] = {1, 2, 4, 8, 16};
  for (int x = 0; x < 5; ++x) t.at(x, 0, 0, 0, 0) = v[x];
  const auto chain = build_mip_chain(t, MipEdge::wrap);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_FLOAT_EQ(chain[1].at(0, 0, 0, 0, 0), (1 + 2 + 0.5f * 4) / 2.5f);
  EXPECT_FLOAT_EQ(chain[1].at(1, 0, 0, 0, 0), (0.5f * 4 + 8 + 16) / 2.5f);
  // 3 -> 1 averages all three.
  Texture u(3, 1, 1, 1, {"R"});
  for (int x = 0; x < 3; ++x) u.at(x, 0, 0, 0, 0) = v[x];
  EXPECT_FLOAT_EQ(build_mip_chain(u, MipEdge::wrap)[1].at(0, 0, 0, 0, 0), 7.0f / 3.0f);
}

TEST(MipChain, PreservesMeanAtEveryLevel) {
  for (const auto& shape : {std::array<int, 3>{16, 8, 1}, std::array<int, 3>{7, 13, 1},
                            std::array<int, 3>{8, 8, 8}, std::array<int, 3>{5, 6, 9}}) {
    Texture t(shape[0], shape[1], shape[2], 1, {"R", "G"});
    for (size_t i = 0; i < t.data.size(); ++i)
      t.data[i] = float((i * 2654435761u) % 1000) / 7.0f;  // deterministic scramble
    const double mean_r = channel_mean(t, 0, 0), mean_g = channel_mean(t, 0, 1);
    for (const Texture& level : build_mip_chain(t, MipEdge::wrap)) {
      EXPECT_NEAR(channel_mean(level, 0, 0), mean_r, 1e-5 * mean_r) << level.shape_string();
      EXPECT_NEAR(channel_mean(level, 0, 1), mean_g, 1e-5 * mean_g) << level.shape_string();
    }
  }
}

TEST(MipChain, ConstantStaysConstant) {
  Texture t(9, 6, 5, 1, {"R"});
  std::fill(t.data.begin(), t.data.end(), 0.3f);
  for (const Texture& level : build_mip_chain(t, MipEdge::clamp))
    for (float v : level.data) ASSERT_NEAR(v, 0.3f, 1e-6f) << level.shape_string();
}

// Largest jump between x-neighbours inside the texture and across the wrap
// seam (last column to first), over all rows; same for y.
struct Jumps {
  double interior = 0, seam = 0;
};
Jumps jumps_x(const Texture& t) {
  Jumps j;
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x + 1 < t.width; ++x)
      j.interior =
          std::max(j.interior, double(std::abs(t.at(x + 1, y, 0, 0, 0) - t.at(x, y, 0, 0, 0))));
    j.seam =
        std::max(j.seam, double(std::abs(t.at(0, y, 0, 0, 0) - t.at(t.width - 1, y, 0, 0, 0))));
  }
  return j;
}
Jumps jumps_y(const Texture& t) {
  Jumps j;
  for (int x = 0; x < t.width; ++x) {
    for (int y = 0; y + 1 < t.height; ++y)
      j.interior =
          std::max(j.interior, double(std::abs(t.at(x, y + 1, 0, 0, 0) - t.at(x, y, 0, 0, 0))));
    j.seam =
        std::max(j.seam, double(std::abs(t.at(x, 0, 0, 0, 0) - t.at(x, t.height - 1, 0, 0, 0))));
  }
  return j;
}

Texture periodic_texture(int w, int h) {
  Texture t(w, h, 1, 1, {"R"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = 2 * kPi * (x + 0.5) / w, v = 2 * kPi * (y + 0.5) / h;
      t.at(x, y, 0, 0, 0) = float(std::sin(u) + 0.5 * std::sin(3 * u + 1.0) * std::cos(2 * v) +
                                  0.3 * std::cos(v + 0.4));
    }
  return t;
}

TEST(MipChain, PeriodicTextureTilesAtEveryLevel) {
  // Power-of-two and non-power-of-two sizes: the seam must look like any
  // interior neighbour pair. Checked on levels with at least 8 texels along
  // the axis; on coarser levels the seam is one of so few pairs that it may
  // be the largest by chance (the roll test below covers those).
  for (const auto& size : {std::array<int, 2>{64, 32}, std::array<int, 2>{48, 40}}) {
    const auto chain = build_mip_chain(periodic_texture(size[0], size[1]), MipEdge::wrap);
    for (const Texture& level : chain) {
      if (level.width >= 8) {
        const Jumps j = jumps_x(level);
        EXPECT_LE(j.seam, j.interior * (1 + 1e-5) + 1e-6) << level.shape_string();
      }
      if (level.height >= 8) {
        const Jumps j = jumps_y(level);
        EXPECT_LE(j.seam, j.interior * (1 + 1e-5) + 1e-6) << level.shape_string();
      }
    }
  }
}

Texture rolled(const Texture& t, int dx, int dy) {
  Texture r = t;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x)
      r.at(wrap_index(x + dx, t.width), wrap_index(y + dy, t.height), 0, 0, 0) =
          t.at(x, y, 0, 0, 0);
  return r;
}

TEST(MipChain, SeamIsFilteredLikeTheInterior) {
  // Rolling a tileable texture moves its seam into the interior. Filtering
  // commutes with a roll by a multiple of the footprint: level L of the rolled
  // texture is level L of the original rolled by (16, 8) >> L. This holds on
  // every level where both rolls stay whole and each step halves exactly
  // (48x40 -> 24x20 -> 12x10 -> 6x5).
  const Texture t = periodic_texture(48, 40);
  const auto chain = build_mip_chain(t, MipEdge::wrap);
  const auto chain_rolled = build_mip_chain(rolled(t, 16, 8), MipEdge::wrap);
  for (int level = 0; level <= 3; ++level) {
    const Texture expected = rolled(chain[level], 16 >> level, 8 >> level);
    ASSERT_EQ(chain_rolled[level].data.size(), expected.data.size());
    for (size_t i = 0; i < expected.data.size(); ++i)
      ASSERT_NEAR(chain_rolled[level].data[i], expected.data[i], 1e-6) << level << " " << i;
  }
}

TEST(MipChain, SeamCheckDetectsANonTilingTexture) {
  // The tiling criterion above must be able to fail: a ramp has a seam.
  Texture ramp(32, 4, 1, 1, {"R"});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 32; ++x) ramp.at(x, y, 0, 0, 0) = float(x);
  const Jumps j = jumps_x(build_mip_chain(ramp, MipEdge::wrap)[1]);
  EXPECT_GT(j.seam, j.interior);
}

// One level by the filter's definition, one axis at a time (x, then y,
// then z), each output texel summing its taps from 0.0 in double and
// stored as float, as the texture between two passes holds it.
Texture level_by_definition(const Texture& in) {
  Texture cur = in;
  for (int axis = 0; axis < 3; ++axis) {
    int dims[3] = {cur.width, cur.height, cur.depth};
    const int n_in = dims[axis], n_out = std::max(1, n_in / 2);
    dims[axis] = n_out;
    Texture next(dims[0], dims[1], dims[2], cur.layers, cur.channels);
    for (int l = 0; l < next.layers; ++l)
      for (int z = 0; z < next.depth; ++z)
        for (int y = 0; y < next.height; ++y)
          for (int x = 0; x < next.width; ++x)
            for (int c = 0; c < next.channel_count(); ++c) {
              const int o[3] = {x, y, z};
              const long long lo = (long long)o[axis] * n_in, hi = lo + n_in;
              double sum = 0.0;
              for (long long i = lo / n_out; i * n_out < hi; ++i) {
                const long long overlap = std::min(hi, (i + 1) * n_out) - std::max(lo, i * n_out);
                if (overlap <= 0) continue;
                int at[3] = {x, y, z};
                at[axis] = int(i);
                sum += double(overlap) / double(n_in) * cur.at(at[0], at[1], at[2], l, c);
              }
              next.at(x, y, z, l, c) = float(sum);
            }
    cur = next;
  }
  return cur;
}

TEST(MipChain, EveryLevelIsTheSeparableDefinitionToTheBit) {
  // Cubes and boxes whose axes halve exactly, reach one texel at different
  // levels, or are odd (5, 3: weights by overlap), volumes and arrays.
  struct Shape {
    int w, h, d, layers, channels;
  };
  for (const Shape s : {Shape{8, 8, 8, 1, 4}, Shape{16, 4, 2, 1, 3}, Shape{2, 8, 1, 3, 2},
                        Shape{10, 6, 4, 1, 1}, Shape{5, 4, 3, 1, 2}, Shape{4, 4, 1, 1, 4}}) {
    Texture t(s.w, s.h, s.d, s.layers, std::vector<std::string>(s.channels, "c"));
    for (size_t i = 0; i < t.data.size(); ++i)
      t.data[i] = float(std::sin(double(i) * 1.7) * 3.1 + std::cos(double(i * i) * 0.01));
    const std::vector<Texture> lower = build_lower_mips(t, MipEdge::wrap);
    Texture expected = t;
    for (size_t level = 0; level < lower.size(); ++level) {
      expected = level_by_definition(expected);
      ASSERT_EQ(lower[level].shape_string(), expected.shape_string());
      EXPECT_TRUE(lower[level].data == expected.data)
          << t.shape_string() << " layers " << s.layers << " level " << level + 1;
    }
  }
}

TEST(MipChain, VolumeUsesTwoByTwoByTwoBox) {
  Texture t(2, 2, 2, 1, {"R"});
  for (int i = 0; i < 8; ++i) t.data[i] = float(1 << i);
  const auto chain = build_mip_chain(t, MipEdge::wrap);
  ASSERT_EQ(chain.size(), 2u);
  EXPECT_EQ(chain[1].depth, 1);
  EXPECT_FLOAT_EQ(chain[1].data[0], 255.0f / 8.0f);
}

TEST(MipChain, ArrayLayersFilteredIndependently) {
  Texture t(4, 4, 1, 3, {"R", "G"});
  for (int layer = 0; layer < 3; ++layer)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        t.at(x, y, 0, layer, 0) = float(layer + 1);
        t.at(x, y, 0, layer, 1) = float(10 * layer + x);
      }
  set_meta(t.metadata, "product", std::string("weather"));
  const auto chain = build_mip_chain(t, MipEdge::wrap);
  ASSERT_EQ(chain.size(), 3u);
  for (const Texture& level : chain) {
    EXPECT_EQ(level.layers, 3);
    EXPECT_EQ(level.channels, t.channels);
    EXPECT_EQ(level.metadata, t.metadata);
    for (int layer = 0; layer < 3; ++layer)
      for (int y = 0; y < level.height; ++y)
        for (int x = 0; x < level.width; ++x)
          ASSERT_FLOAT_EQ(level.at(x, y, 0, layer, 0), float(layer + 1));
  }
  // Layer 2, level 2 (1x1): mean of x over 0..3 plus 20.
  EXPECT_FLOAT_EQ(chain[2].at(0, 0, 0, 2, 1), 21.5f);
}

TEST(MipChain, LowerMipsAreTheChainBelowLevelZero) {
  Texture t(12, 7, 5, 1, {"R", "G"});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i % 13) * 0.25f;
  const std::vector<Texture> chain = build_mip_chain(t, MipEdge::wrap);
  const std::vector<Texture> lower = build_lower_mips(t, MipEdge::wrap);
  ASSERT_EQ(lower.size() + 1, chain.size());
  EXPECT_EQ(chain[0].data, t.data);
  for (size_t i = 0; i < lower.size(); ++i) {
    EXPECT_EQ(lower[i].shape_string(), chain[i + 1].shape_string()) << "level " << i + 1;
    EXPECT_EQ(lower[i].data, chain[i + 1].data) << "level " << i + 1;
  }
  EXPECT_TRUE(build_lower_mips(Texture(1, 1, 1, 1, {"R"}), MipEdge::wrap).empty());
}

TEST(MipChain, SameBitsForOneAndTwoThreads) {
  // Odd sizes, so that the footprints of 2 + 1/n texels sum in doubles;
  // rows run in tbb::parallel_for, each texel on its own.
  Texture t(37, 29, 11, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < t.data.size(); ++i)
    t.data[i] = float(std::sin(0.37 * double(i)) * 0.5 + 0.5);
  std::vector<Texture> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = build_mip_chain(t, MipEdge::wrap);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = build_mip_chain(t, MipEdge::wrap);
  }
  ASSERT_EQ(one.size(), two.size());
  for (size_t level = 0; level < one.size(); ++level)
    EXPECT_EQ(one[level].data, two[level].data) << "level " << level;
}

}  // namespace
}  // namespace skybake

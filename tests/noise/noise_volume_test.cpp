// Noise volume bakers (src/noise/noise_volume.hpp): the baked voxels are the
// pure noise functions at texel centres, the volumes tile on every axis, the
// values stay in [0, 1], the output is the same for 1 and 2 threads, channel
// statistics are stable across seeds, spec validation, single-channel packing.
#include "noise/noise_volume.hpp"

#include <atomic>
#include <cmath>
#include <mutex>
#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.hpp"
#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"
#include "noise/worley.hpp"

namespace skybake {
namespace {

// Largest jump between neighbours along `axis` inside the volume and across
// the wrapped face (last texel -> first texel).
struct Jumps {
  float interior = 0, wrap = 0;
};
Jumps jumps(const Texture& t, int channel, int axis) {
  const int size[3] = {t.width, t.height, t.depth};
  Jumps j;
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) {
        int next[3] = {x, y, z};
        const bool wraps = ++next[axis] == size[axis];
        if (wraps) next[axis] = 0;
        const float d =
            std::abs(t.at(x, y, z, 0, channel) - t.at(next[0], next[1], next[2], 0, channel));
        (wraps ? j.wrap : j.interior) = std::max(wraps ? j.wrap : j.interior, d);
      }
  return j;
}

// In a tiling volume the wrapped face is one more face between neighbours,
// drawn from the same distribution of jumps as the n - 1 interior faces: its
// largest jump can exceed theirs, but only by chance and barely (we saw
// 1.0004x). 10% margin; a volume that does not tile jumps by several times
// (TilingCheck below).
constexpr float kWrapMargin = 1.1f;

void expect_tiles(const Texture& t) {
  for (int c = 0; c < t.channel_count(); ++c)
    for (int axis = 0; axis < (t.depth > 1 ? 3 : 2); ++axis) {
      const Jumps j = jumps(t, c, axis);
      EXPECT_GT(j.interior, 0.0f) << t.channels[c] << " axis " << axis;
      EXPECT_LE(j.wrap, kWrapMargin * j.interior) << t.channels[c] << " axis " << axis;
    }
}

void expect_unit_range(const Texture& t) {
  for (size_t i = 0; i < t.data.size(); ++i) {
    ASSERT_GE(t.data[i], 0.0f) << i;
    ASSERT_LE(t.data[i], 1.0f) << i;
  }
}

struct Stats {
  double mean = 0, stddev = 0;
};
Stats channel_stats(const Texture& t, int c) {
  double s = 0, s2 = 0;
  const size_t n = t.texel_count();
  for (size_t i = 0; i < n; ++i) {
    const double v = t.data[i * t.channel_count() + c];
    s += v;
    s2 += v * v;
  }
  return {s / n, std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)))};
}

Texture bake_shape_with_threads(const NoiseShapeSpec& spec, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return bake_noise_shape(spec, {});
}

// One default-size shape volume shared by the tests that only read it.
const Texture& default_shape() {
  static const Texture t = bake_shape_with_threads(NoiseShapeSpec{}, 2);
  return t;
}

TEST(NoiseShape, DefaultShapeChannelsAndMetadata) {
  const Texture& t = default_shape();
  EXPECT_EQ(t.shape_string(), "128x128x128");
  EXPECT_EQ(t.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(meta_string(t.metadata, "product"), "noise_shape");
  EXPECT_EQ(meta_int(t.metadata, "seed"), 0);
  EXPECT_EQ(meta_string(t.metadata, "remap"), "worley_new_min");
  EXPECT_EQ(meta_int(t.metadata, "period.G"), 8);
  EXPECT_EQ(meta_int(t.metadata, "period.B"), 16);
  EXPECT_EQ(meta_int(t.metadata, "period.A"), 32);
  EXPECT_EQ(meta_int(t.metadata, "octaves.A"), 2);
  for (const char* c : {"channel.R", "channel.G", "channel.B", "channel.A"})
    EXPECT_FALSE(meta_string(t.metadata, c).empty());
}

TEST(NoiseShape, ValuesInUnitRangeAndTiling) {
  expect_unit_range(default_shape());
  expect_tiles(default_shape());
}

TEST(NoiseShape, VoxelsAreThePureFunctionsAtTexelCentres) {
  const NoiseShapeSpec spec;
  const Texture& t = default_shape();
  const int n = spec.size;
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> idx(0, n - 1);
  for (int i = 0; i < 300; ++i) {
    const int x = idx(rng), y = idx(rng), z = idx(rng);
    auto at = [&](int period) {
      return glm::vec3(cell_coord_from_texel(x, n, period), cell_coord_from_texel(y, n, period),
                       cell_coord_from_texel(z, n, period));
    };
    for (int c = 0; c < 3; ++c) {
      const WorleyFbmSpec& w = spec.worley[c];
      // Same hash, same feature points, same float operations: the same bits.
      ASSERT_EQ(t.at(x, y, z, 0, c + 1),
                worley_fbm3(at(w.period), glm::ivec3(w.period), w.octaves, spec.seed));
    }
    const float perlin = perlin_fbm3(at(spec.perlin_period), glm::ivec3(spec.perlin_period),
                                     spec.perlin_octaves, spec.seed, spec.perlin_gain);
    const float worley =
        worley_fbm3(at(spec.perlin_worley.period), glm::ivec3(spec.perlin_worley.period),
                    spec.perlin_worley.octaves, spec.seed);
    // The Perlin rows interpolate in another order: equal to rounding.
    ASSERT_NEAR(t.at(x, y, z, 0, 0), perlin_worley(perlin, worley, spec.remap), 1e-5f);
  }
}

TEST(NoiseShape, SameDataForOneAndTwoThreads) {
  const Texture one = bake_shape_with_threads(NoiseShapeSpec{}, 1);
  EXPECT_TRUE(one.data == default_shape().data);
  EXPECT_EQ(one.metadata, default_shape().metadata);
}

TEST(NoiseShape, ChannelStatisticsAreStableAcrossSeeds) {
  // A channel's volume mean averages ~period^3 independent cells of its
  // coarsest octave; with a per-voxel spread <= 0.2 and >= 8^3 cells its
  // seed-to-seed standard deviation is <= 0.2 / sqrt(512) ~ 0.009. We allow
  // 0.03 (> 3 sigma) around the mean of 5 seeds, and 20% on the spread.
  std::vector<Texture> bakes;
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    NoiseShapeSpec spec;
    spec.seed = seed;
    bakes.push_back(bake_noise_shape(spec, {}));
  }
  EXPECT_FALSE(bakes[0].data == bakes[1].data);
  for (int c = 0; c < 4; ++c) {
    Stats avg;
    for (const Texture& t : bakes) {
      avg.mean += channel_stats(t, c).mean / 5;
      avg.stddev += channel_stats(t, c).stddev / 5;
    }
    EXPECT_GT(avg.stddev, 0.03) << "channel " << c;  // not flat
    for (const Texture& t : bakes) {
      const Stats s = channel_stats(t, c);
      EXPECT_NEAR(s.mean, avg.mean, 0.03) << "channel " << c;
      EXPECT_NEAR(s.stddev / avg.stddev, 1.0, 0.2) << "channel " << c;
    }
  }
}

TEST(NoiseShape, EveryRemapVariantBakesInRangeAndTiles) {
  for (PerlinWorleyRemap remap : {PerlinWorleyRemap::worley_new_min,
                                  PerlinWorleyRemap::worley_old_min, PerlinWorleyRemap::dilate}) {
    NoiseShapeSpec spec;
    spec.size = 32;
    spec.perlin_period = 2;
    spec.perlin_worley = {2, 3};
    spec.worley = {{{2, 3}, {4, 2}, {8, 1}}};
    spec.remap = remap;
    ASSERT_TRUE(spec_problems(spec).empty());
    const Texture t = bake_noise_shape(spec, {});
    SCOPED_TRACE(remap_name(remap));
    expect_unit_range(t);
    expect_tiles(t);
    EXPECT_EQ(meta_string(t.metadata, "remap"), remap_name(remap));
  }
}

TEST(NoiseShape, ReportsProgressToOne) {
  std::mutex m;
  double last_max = 0;
  int calls = 0;
  BakeContext ctx;
  ctx.on_progress = [&](double f) {
    std::lock_guard<std::mutex> lock(m);
    last_max = std::max(last_max, f);
    ++calls;
  };
  NoiseShapeSpec spec;
  spec.size = 16;
  spec.perlin_period = 2;
  spec.perlin_worley = {2, 2};
  spec.worley = {{{2, 2}, {4, 1}, {8, 1}}};
  bake_noise_shape(spec, ctx);
  EXPECT_EQ(calls, 16);
  EXPECT_EQ(last_max, 1.0);
}

TEST(NoiseDetail, DefaultDetailVolume) {
  const NoiseDetailSpec spec;
  Texture t, one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    t = bake_noise_detail(spec, {});
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_noise_detail(spec, {});
  }
  EXPECT_EQ(t.shape_string(), "32x32x32");
  EXPECT_EQ(t.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(meta_string(t.metadata, "product"), "noise_detail");
  EXPECT_TRUE(one.data == t.data);
  expect_unit_range(t);
  expect_tiles(t);
  const uint32_t seed = stream_seed(spec.seed, kDetailStream);
  for (int z = 0; z < 32; z += 5)
    for (int y = 0; y < 32; y += 3)
      for (int x = 0; x < 32; x += 7)
        for (int c = 0; c < 3; ++c) {
          const int p = spec.worley[c].period;
          const glm::vec3 q(cell_coord_from_texel(x, 32, p), cell_coord_from_texel(y, 32, p),
                            cell_coord_from_texel(z, 32, p));
          ASSERT_EQ(t.at(x, y, z, 0, c),
                    worley_fbm3(q, glm::ivec3(p), spec.worley[c].octaves, seed));
        }
}

TEST(NoiseDetail, StatisticsStableAcrossSeedsAndUnrelatedToTheShape) {
  // 32^3 with coarsest period 2: only 8 cells, so the means move more; the
  // finer channels (4^3 and 8^3 cells) are held tighter. Bound: 0.2 / sqrt(cells).
  std::vector<Texture> bakes;
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    NoiseDetailSpec spec;
    spec.seed = seed;
    bakes.push_back(bake_noise_detail(spec, {}));
  }
  const double tolerance[3] = {0.2, 0.1, 0.04};
  for (int c = 0; c < 3; ++c) {
    double avg = 0;
    for (const Texture& t : bakes) avg += channel_stats(t, c).mean / 5;
    for (const Texture& t : bakes) EXPECT_NEAR(channel_stats(t, c).mean, avg, tolerance[c]) << c;
  }
  // Same seed, same period (8 appears in both): different fields.
  NoiseShapeSpec shape;
  shape.size = 32;
  shape.perlin_period = 2;
  shape.perlin_worley = {2, 1};
  shape.worley = {{{8, 1}, {8, 1}, {8, 1}}};
  NoiseDetailSpec detail;
  detail.worley = {{{8, 1}, {8, 1}, {8, 1}}};
  const Texture a = bake_noise_shape(shape, {}), b = bake_noise_detail(detail, {});
  int equal = 0;
  for (size_t i = 0; i < b.texel_count(); ++i) equal += a.data[i * 4 + 1] == b.data[i * 3];
  EXPECT_LT(equal, int(b.texel_count() / 100));
}

TEST(NoiseVolumeSpec, DefaultsAreValidAndBadFieldsAreNamed) {
  EXPECT_TRUE(spec_problems(NoiseShapeSpec{}).empty());
  EXPECT_TRUE(spec_problems(NoiseDetailSpec{}).empty());
  auto fields = [](const std::vector<SpecProblem>& problems) {
    std::vector<std::string> f;
    for (const SpecProblem& p : problems) f.push_back(p.field);
    return f;
  };
  NoiseShapeSpec shape;
  shape.size = 64;  // B: 16 * 4 and A: 32 * 2 = 64 > 32 cells: under 2 voxels per cell
  EXPECT_EQ(fields(spec_problems(shape)), (std::vector<std::string>{"worley[1]", "worley[2]"}));
  shape = {};
  shape.perlin_octaves = 0;
  shape.perlin_gain = 0.0f;
  shape.worley[1].period = 0;
  EXPECT_EQ(fields(spec_problems(shape)),
            (std::vector<std::string>{"perlin.octaves", "perlin_gain", "worley[1].period"}));
  const std::vector<SpecProblem> p = spec_problems(shape);
  EXPECT_EQ(p[0].message, "expected 1 .. 8, got 0");
  NoiseDetailSpec detail;
  detail.size = 1;
  EXPECT_EQ(fields(spec_problems(detail)).front(), "size");
  EXPECT_THROW(bake_noise_detail(detail, {}), Error);
  EXPECT_THROW(bake_noise_shape(shape, {}), Error);
}

TEST(PackSingleChannel, FormulasOnKnownTexels) {
  Texture t(2, 1, 1, 1, {"R", "G", "B", "A"});
  t.data = {0.5f, 1.0f, 1.0f, 1.0f,   // fbm = 1: (0.5 + 0) / 1
            0.0f, 0.0f, 0.0f, 0.0f};  // fbm = 0: (0 + 1) / 2
  set_meta(t.metadata, "channel.G", "worley");
  const Texture shape = pack_single_channel(t, shape_pack_weights());
  EXPECT_EQ(shape.channels, std::vector<std::string>{"R"});
  EXPECT_FLOAT_EQ(shape.data[0], 0.5f);
  EXPECT_FLOAT_EQ(shape.data[1], 0.5f);
  EXPECT_EQ(meta_string(shape.metadata, "source.channel.G"), "worley");
  EXPECT_EQ(shape.metadata.count("channel.G"), 0u);
  EXPECT_FALSE(meta_string(shape.metadata, "packed").empty());

  Texture d(1, 1, 1, 1, {"R", "G", "B"});
  d.data = {0.8f, 0.4f, 0.2f};
  EXPECT_FLOAT_EQ(pack_single_channel(d, detail_pack_weights()).data[0],
                  0.625f * 0.8f + 0.25f * 0.4f + 0.125f * 0.2f);
  Texture one(1, 1, 1, 1, {"R"});
  EXPECT_THROW(pack_single_channel(one, shape_pack_weights()), Error);
  PackWeights heavy = detail_pack_weights();
  heavy.weights = {{1.0f, 1.0f, 0.0f, 0.0f}};
  EXPECT_THROW(pack_single_channel(d, heavy), Error);
}

TEST(PackSingleChannel, PackedVolumesStayInRangeAndTile) {
  const Texture packed = pack_single_channel(default_shape(), shape_pack_weights());
  EXPECT_EQ(packed.shape_string(), "128x128x128");
  expect_unit_range(packed);
  expect_tiles(packed);
}

TEST(TilingCheck, CatchesAVolumeThatDoesNotTile) {
  // The helper itself must be able to fail: Worley sampled over 3.5 of its 4
  // cells jumps at the wrapped face.
  Texture t(32, 32, 32, 1, {"R"});
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        t.at(x, y, z, 0, 0) = worley3_inverted(
            glm::vec3(x + 0.5f, y + 0.5f, z + 0.5f) * (3.5f / 32), glm::ivec3(4), 1u);
  for (int axis = 0; axis < 3; ++axis) {
    const Jumps j = jumps(t, 0, axis);
    EXPECT_GT(j.wrap, 2 * kWrapMargin * j.interior) << axis;
  }
}

}  // namespace
}  // namespace skybake

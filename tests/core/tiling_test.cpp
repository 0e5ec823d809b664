// measure_tiling: tileable textures pass on every axis, level and layer; a
// step seam, a ramp, a mirrored (kinked) seam, a crop and a ramp in one mip
// level fail where they are; white noise and too small textures cannot
// tell; constants pass; the limits follow the interior distribution.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/math.hpp"
#include "core/mip_chain.hpp"
#include "core/tiling.hpp"

namespace skybake {
namespace {

// Smooth tileable noise in [0, 1]: a sum of cosines with integer wave
// numbers (up to `max_k` periods per tile) and random phases.
Texture smooth_noise(int w, int h, int d, uint32_t seed, int channels = 1, int max_k = 4) {
  static const char* names[] = {"R", "G", "B", "A"};
  Texture t(w, h, d, 1, std::vector<std::string>(names, names + channels));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> k(-max_k, max_k);
  std::uniform_real_distribution<double> phase(0.0, 2 * kPi);
  for (int c = 0; c < channels; ++c) {
    struct Wave {
      int kx, ky, kz;
      double phase, amplitude;
    };
    std::vector<Wave> waves;
    while (waves.size() < 12) {
      Wave wv{k(rng), k(rng), d > 1 ? k(rng) : 0, phase(rng), 0.0};
      const double len = std::sqrt(double(wv.kx * wv.kx + wv.ky * wv.ky + wv.kz * wv.kz));
      if (len == 0.0) continue;
      wv.amplitude = 1.0 / len;
      waves.push_back(wv);
    }
    double lo = 1e300, hi = -1e300;
    for (int z = 0; z < d; ++z)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          double v = 0.0;
          for (const Wave& wv : waves)
            v += wv.amplitude * std::cos(2 * kPi * (wv.kx * (x + 0.5) / w + wv.ky * (y + 0.5) / h +
                                                    wv.kz * (z + 0.5) / d) +
                                         wv.phase);
          t.at(x, y, z, 0, c) = float(v);
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
    for (int z = 0; z < d; ++z)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          float& v = t.at(x, y, z, 0, c);
          v = float((v - lo) / (hi - lo));
        }
  }
  return t;
}

const AxisTiling& entry(const TilingReport& r, int level, char axis, const std::string& channel,
                        int layer = 0) {
  for (const AxisTiling& a : r.axes)
    if (a.level == level && a.axis == axis && a.channel == channel && a.layer == layer) return a;
  throw std::runtime_error("no such entry");
}

TEST(Tiling, SmoothTileableNoiseTilesOnEveryAxisAndChannel) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Texture t = smooth_noise(48, 40, 32, seed, 2);
    const TilingReport r = measure_tiling(t, 0.25);
    EXPECT_EQ(r.verdict, TilingVerdict::tiles) << seed << " worst " << r.worst_ratio;
    EXPECT_EQ(r.axes.size(), 6u);
    for (const AxisTiling& a : r.axes) {
      EXPECT_EQ(a.verdict, TilingVerdict::tiles) << a.axis << a.channel;
      EXPECT_LE(a.values.seam, a.values.limit);
      EXPECT_LE(a.slopes.seam, a.slopes.limit);
      EXPECT_GT(a.contrast, 2.0) << "smooth: far texels differ much more than neighbours";
    }
  }
}

TEST(Tiling, StepSeamOfFortyLevelsFailsOnItsAxisOnly) {
  // The last x-plane raised by 40/255: a step at the seam (and one face
  // before it), on a noise whose interior jumps reach more than that.
  Texture t = smooth_noise(64, 64, 64, 7, 1, 8);
  double largest_jump = 0.0;
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x + 1 < 64; ++x)
        largest_jump = std::max(largest_jump, double(std::abs(t.at(x + 1, y, z, 0, 0) -
                                                              t.at(x, y, z, 0, 0))));
  ASSERT_GT(largest_jump, 40.0 / 255.0) << "the old single-maximum statistic would pass it";
  ASSERT_EQ(measure_tiling(t, 0.25).verdict, TilingVerdict::tiles);
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y) t.at(63, y, z, 0, 0) += 40.0f / 255.0f;
  const TilingReport r = measure_tiling(t, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::seam);
  EXPECT_FALSE(r.tiles);
  EXPECT_EQ(entry(r, 0, 'x', "R").verdict, TilingVerdict::seam);
  EXPECT_GT(entry(r, 0, 'x', "R").values.seam, entry(r, 0, 'x', "R").values.limit);
  EXPECT_EQ(entry(r, 0, 'y', "R").verdict, TilingVerdict::tiles);
  EXPECT_EQ(entry(r, 0, 'z', "R").verdict, TilingVerdict::tiles);
  EXPECT_GT(r.worst_ratio, 1.0);
}

TEST(Tiling, RampFailsOnItsAxisOnlyAndConstantsPass) {
  Texture t(32, 32, 1, 1, {"R"});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) t.at(x, y, 0, 0, 0) = float(x);
  const TilingReport r = measure_tiling(t, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::seam);
  ASSERT_EQ(r.axes.size(), 2u);
  EXPECT_EQ(r.axes[0].axis, 'x');
  EXPECT_EQ(r.axes[0].verdict, TilingVerdict::seam);
  EXPECT_FALSE(r.axes[0].tiles);
  // Interior jumps are 1 on both sides of every face, the seam jumps 31.
  EXPECT_DOUBLE_EQ(r.axes[0].values.seam, 31.0);
  EXPECT_DOUBLE_EQ(r.axes[0].values.median, 1.0);
  EXPECT_DOUBLE_EQ(r.axes[0].values.limit, 1.25);
  EXPECT_EQ(r.axes[1].verdict, TilingVerdict::tiles);
  EXPECT_EQ(r.axes[1].reason, "constant");
  EXPECT_TRUE(measure_tiling(Texture(16, 16, 16, 1, {"R"}), 0.25).tiles);
}

TEST(Tiling, MirroredSeamFailsOnSlopes) {
  // Values meet at the seam (v(n-1) = v(0)) but the slope flips there: a
  // non-periodic smooth curve mirrored to make it "tile".
  Texture t(64, 32, 1, 1, {"R"});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const int m = x < 32 ? x : 63 - x;
      t.at(x, y, 0, 0, 0) = float(std::sin(0.09 * m + 0.2 * y) + 0.03 * m);
    }
  const TilingReport r = measure_tiling(t, 0.25);
  const AxisTiling& x = entry(r, 0, 'x', "R");
  EXPECT_LE(x.values.seam, x.values.limit) << "the values meet";
  EXPECT_GT(x.slopes.seam, x.slopes.limit) << "the slope turns";
  EXPECT_EQ(x.verdict, TilingVerdict::seam);
}

TEST(Tiling, WhiteNoiseCannotTell) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const auto& shape : {std::array<int, 3>{128, 128, 1}, std::array<int, 3>{32, 32, 32}}) {
    Texture t(shape[0], shape[1], shape[2], 1, {"R"});
    for (float& v : t.data) v = u(rng);
    const TilingReport r = measure_tiling(t, 0.25);
    EXPECT_EQ(r.verdict, TilingVerdict::cannot_tell);
    EXPECT_FALSE(r.tiles);
    for (const AxisTiling& a : r.axes) {
      EXPECT_EQ(a.verdict, TilingVerdict::cannot_tell);
      EXPECT_NEAR(a.contrast, 1.0, 0.05) << "far texels differ like neighbours";
      EXPECT_NE(a.reason.find("too rough"), std::string::npos) << a.reason;
    }
  }
}

TEST(Tiling, ARoughChannelIsNotJudgedWhenAnotherIsAlongItsAxis) {
  Texture t = smooth_noise(64, 64, 1, 6, 2);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) t.at(x, y, 0, 0, 1) = u(rng);  // G: white noise
  TilingReport r = measure_tiling(t, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::tiles);
  EXPECT_EQ(entry(r, 0, 'x', "G").verdict, TilingVerdict::not_judged);
  EXPECT_NE(entry(r, 0, 'x', "G").reason.find("judged on channel R"), std::string::npos);
  // A crop cuts both channels: R shows it.
  Texture cropped(50, 64, 1, 1, {"R", "G"});
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 50; ++x)
      for (int c = 0; c < 2; ++c) cropped.at(x, y, 0, 0, c) = t.at(x, y, 0, 0, c);
  r = measure_tiling(cropped, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::seam);
  EXPECT_EQ(entry(r, 0, 'x', "R").verdict, TilingVerdict::seam);
}

TEST(Tiling, SharpPeriodicFeaturesTileAndACropShows) {
  // Steep but periodic: a smooth noise pushed through a steep ramp has
  // interior jumps near 1, like the cirrus streaks across their fibres.
  Texture t = smooth_noise(256, 256, 1, 5, 1, 6);
  for (float& v : t.data) v = float(std::clamp(0.5 + 12.0 * (v - 0.5), 0.0, 1.0));
  const TilingReport whole = measure_tiling(t, 0.25);
  EXPECT_EQ(whole.verdict, TilingVerdict::tiles) << whole.worst_ratio;
  Texture cropped(256, 200, 1, 1, {"R"});
  std::copy(t.data.begin(), t.data.begin() + cropped.data.size(), cropped.data.begin());
  const TilingReport r = measure_tiling(cropped, 0.25);
  EXPECT_EQ(entry(r, 0, 'y', "R").verdict, TilingVerdict::seam);
  EXPECT_EQ(entry(r, 0, 'x', "R").verdict, TilingVerdict::tiles);
}

TEST(Tiling, EveryMipLevelIsMeasuredAndARampLevelFails) {
  const Texture t = smooth_noise(128, 128, 1, 4, 2, 4);
  std::vector<Texture> chain = build_mip_chain(t, MipEdge::wrap);
  std::vector<Texture> lower(chain.begin() + 1, chain.end());
  const TilingReport r = measure_tiling(chain[0], lower, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::tiles) << r.worst_ratio;
  EXPECT_EQ(entry(r, 2, 'x', "G").verdict, TilingVerdict::tiles) << "32 texels are judged";
  EXPECT_EQ(entry(r, 3, 'x', "G").verdict, TilingVerdict::not_judged) << "16 are not";
  EXPECT_TRUE(entry(r, 3, 'x', "G").tiles);
  size_t entries = 0;
  for (size_t level = 0; level < chain.size(); ++level)
    entries += chain[level].width > 1 ? 4 : 0;  // 2 axes x 2 channels
  EXPECT_EQ(r.axes.size(), entries);

  Texture& ramp = lower[0];  // level 1, 64x64
  for (int y = 0; y < ramp.height; ++y)
    for (int x = 0; x < ramp.width; ++x) ramp.at(x, y, 0, 0, 0) = float(x) / 64.0f;
  const TilingReport bad = measure_tiling(chain[0], lower, 0.25);
  EXPECT_EQ(bad.verdict, TilingVerdict::seam);
  EXPECT_EQ(entry(bad, 1, 'x', "R").verdict, TilingVerdict::seam);
  EXPECT_EQ(entry(bad, 1, 'x', "G").verdict, TilingVerdict::tiles);
  EXPECT_EQ(entry(bad, 0, 'x', "R").verdict, TilingVerdict::tiles);
}

TEST(Tiling, LayersAreMeasuredOneByOne) {
  const Texture noise = smooth_noise(32, 32, 1, 9);
  Texture t(32, 32, 1, 2, {"R"});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      t.at(x, y, 0, 0, 0) = noise.at(x, y, 0, 0, 0);
      t.at(x, y, 0, 1, 0) = float(y);  // layer 1 ramps along y
    }
  const TilingReport r = measure_tiling(t, 0.25);
  EXPECT_EQ(r.verdict, TilingVerdict::seam);
  EXPECT_EQ(r.axes.size(), 4u);
  EXPECT_EQ(entry(r, 0, 'y', "R", 0).verdict, TilingVerdict::tiles);
  EXPECT_EQ(entry(r, 0, 'y', "R", 1).verdict, TilingVerdict::seam);
}

TEST(Tiling, ShortAxesCannotTellAtLevelZero) {
  const Texture t = smooth_noise(64, 8, 1, 3);
  const TilingReport r = measure_tiling(t, 0.25);
  EXPECT_EQ(entry(r, 0, 'x', "R").verdict, TilingVerdict::tiles);
  EXPECT_EQ(entry(r, 0, 'y', "R").verdict, TilingVerdict::cannot_tell);
  EXPECT_NE(entry(r, 0, 'y', "R").reason.find("8 texels"), std::string::npos);
  EXPECT_EQ(r.verdict, TilingVerdict::cannot_tell);
}

TEST(Tiling, LimitsFollowTheInteriorSpread) {
  // Interior faces that vary more give the seam more room, never less than
  // the tolerance.
  const Texture t = smooth_noise(64, 64, 1, 8);
  for (const AxisTiling& a : measure_tiling(t, 0.25).axes) {
    EXPECT_GE(a.values.limit, 1.25 * a.values.median - 1e-12);
    EXPECT_GE(a.values.limit, a.values.median + 4 * (a.values.q90 - a.values.median) - 1e-12);
    EXPECT_GE(a.slopes.limit, 2.5 * a.slopes.median - 1e-12);
  }
  for (const AxisTiling& a : measure_tiling(t, 1.0).axes)
    EXPECT_GE(a.values.limit, 2.0 * a.values.median - 1e-12);
}

}  // namespace
}  // namespace skybake

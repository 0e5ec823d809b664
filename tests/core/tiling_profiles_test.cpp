// compute_tiling_profiles against the statistic's definition written out
// line by line (core/tiling.hpp), with every index wrapped: the same doubles
// to the last bit on volumes, 2D arrays, 2D textures, odd and tiny axes
// (3 texels: the padding wraps more than once) and several channels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/tiling_profiles.hpp"
#include "support/simd_targets.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

Texture random_texture(int w, int h, int d, int layers, int channels, uint32_t seed) {
  static const char* names[] = {"R", "G", "B", "A"};
  Texture t(w, h, d, layers, std::vector<std::string>(names, names + channels));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1.0f, 3.0f);
  for (float& v : t.data) v = value(rng);
  return t;
}

// The definition, one line of texels at a time, lines in plane order (the
// first other axis fastest).
TilingProfiles profiles_by_definition(const Texture& t, int layer, int channel, int axis) {
  const int n[3] = {t.width, t.height, t.depth};
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  auto w = [len](int i) { return ((i % len) + len) % len; };
  std::vector<int> lags;
  for (int k : {2, 3, 4, 5})
    if (len / k >= 2 && std::find(lags.begin(), lags.end(), len / k) == lags.end())
      lags.push_back(len / k);
  TilingProfiles p;
  for (auto* v : {&p.jump, &p.jump_side, &p.turn, &p.turn_side}) v->assign(len, 0.0);
  std::vector<double> x(len), d(len), k(len);
  long double far = 0.0;
  double lines = 0.0;
  for (int v = 0; v < n[v_axis]; ++v)
    for (int u = 0; u < n[u_axis]; ++u) {
      int c[3] = {0, 0, 0};
      c[u_axis] = u;
      c[v_axis] = v;
      for (int i = 0; i < len; ++i) {
        c[axis] = i;
        x[i] = double(t.at(c[0], c[1], c[2], layer, channel));
      }
      for (int f = 0; f < len; ++f) d[f] = x[w(f + 1)] - x[f];
      for (int f = 0; f < len; ++f) k[f] = std::abs(d[w(f + 1)] - d[w(f - 1)]);
      for (int f = 0; f < len; ++f) d[f] = std::abs(d[f]);
      for (int f = 0; f < len; ++f) {
        p.jump[f] += d[f];
        p.jump_side[f] += std::max(d[w(f - 2)] + d[w(f - 1)], d[w(f + 1)] + d[w(f + 2)]) / 2;
        p.turn[f] += k[f];
        p.turn_side[f] += std::max(k[w(f - 3)] + k[w(f - 2)], k[w(f + 2)] + k[w(f + 3)]) / 2;
      }
      double line_far = 0.0;
      for (int lag : lags)
        for (int i = 0; i < len; ++i) line_far += std::abs(x[w(i + lag)] - x[i]);
      far += line_far;
      lines += 1.0;
    }
  for (auto* v : {&p.jump, &p.jump_side, &p.turn, &p.turn_side})
    for (double& e : *v) e /= lines;
  p.far = lags.empty() ? 0.0 : double(far / (lines * len * lags.size()));
  return p;
}

void expect_definition(const Texture& t) {
  const int n[3] = {t.width, t.height, t.depth};
  for (int layer = 0; layer < t.layers; ++layer)
    for (int axis = 0; axis < 3; ++axis) {
      if (n[axis] < 2) continue;
      const std::vector<TilingProfiles> fast = compute_tiling_profiles(t, layer, axis);
      ASSERT_EQ(fast.size(), t.channels.size());
      for (int c = 0; c < t.channel_count(); ++c) {
        SCOPED_TRACE(::testing::Message() << t.shape_string() << " layer " << layer << " axis "
                                          << axis << " channel " << c);
        const TilingProfiles slow = profiles_by_definition(t, layer, c, axis);
        // Exact: the same terms are added in the same order.
        EXPECT_EQ(fast[c].jump, slow.jump);
        EXPECT_EQ(fast[c].jump_side, slow.jump_side);
        EXPECT_EQ(fast[c].turn, slow.turn);
        EXPECT_EQ(fast[c].turn_side, slow.turn_side);
        EXPECT_EQ(fast[c].far, slow.far);
      }
    }
}

TEST(TilingProfiles, VolumeOfFourChannelsMatchesTheDefinitionExactly) {
  expect_definition(random_texture(24, 17, 20, 1, 4, 1));
}

// Four channels take the kernel core/kernels/tiling_rgba.hpp (a texel's
// channels in the lanes, lines read 32 at a time, far jumps 4 lines side by
// side), on every SIMD target this CPU runs: line counts that leave partial
// chunks and blocks, tiny axes, 2D arrays.
TEST_P(KernelsOnEachTarget, TilingFourChannelsMatchTheDefinition) {
  expect_definition(random_texture(37, 35, 33, 1, 4, 5));
  expect_definition(random_texture(3, 2, 5, 1, 4, 6));
  expect_definition(random_texture(40, 6, 1, 2, 4, 7));
}

TEST(TilingProfiles, TinyAxesWrapTheirPaddingMoreThanOnce) {
  expect_definition(random_texture(3, 2, 5, 1, 2, 2));
}

TEST(TilingProfiles, TwoDimensionalArraysMatchLayerByLayer) {
  expect_definition(random_texture(19, 33, 1, 3, 3, 3));
}

TEST(TilingProfiles, SingleChannelPlaneMatches) {
  expect_definition(random_texture(64, 40, 1, 1, 1, 4));
}

}  // namespace
}  // namespace skybake

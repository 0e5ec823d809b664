// The curl texture baker (src/noise/curl_texture.hpp): texels decode to the
// curl functions at texel centres, the scale makes each channel span [0, 1],
// the baked field is nearly divergence free (against a control), tiles, and
// is the same for 1 and 2 threads.
#include "noise/curl_texture.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.hpp"
#include "noise/curl.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"

namespace skybake {
namespace {

Texture bake_with_threads(const CurlSpec& spec, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return bake_curl(spec, {});
}

float decoded(const Texture& t, int x, int y, int c, float scale) {
  return (2.0f * t.at(x, y, 0, 0, c) - 1.0f) * scale;
}

TEST(CurlTexture, DecodesToTheCurlAtTexelCentres) {
  const CurlSpec spec;
  const Texture t = bake_with_threads(spec, 2);
  EXPECT_EQ(t.shape_string(), "128x128");
  EXPECT_EQ(t.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(meta_string(t.metadata, "product"), "curl");
  const float scale_rg = float(meta_double(t.metadata, "curl_scale_rg"));
  const float scale_b = float(meta_double(t.metadata, "curl_scale_b"));
  for (int y = 0; y < 128; y += 9)
    for (int x = 0; x < 128; x += 7) {
      const glm::vec2 p(cell_coord_from_texel(x, 128, spec.period),
                        cell_coord_from_texel(y, 128, spec.period));
      const glm::vec2 v = curl2(p, glm::ivec2(spec.period), spec.octaves, spec.seed, spec.gain);
      const glm::vec3 v3 = curl3({p, spec.slice_z}, glm::ivec3(spec.period), spec.octaves,
                                 stream_seed(spec.seed, 0x33643344), spec.gain);
      EXPECT_NEAR(decoded(t, x, y, 0, scale_rg), v.x, 1e-5f * scale_rg);
      EXPECT_NEAR(decoded(t, x, y, 1, scale_rg), v.y, 1e-5f * scale_rg);
      EXPECT_NEAR(decoded(t, x, y, 2, scale_b), v3.z, 1e-5f * scale_b);
    }
}

TEST(CurlTexture, WithoutZIsRAndGOfTheFullTexture) {
  // R and G do not depend on B: the two-channel texture is the first two
  // channels of the three-channel one, bit for bit, with no B metadata.
  CurlSpec spec;
  spec.size = 32;
  const Texture rgb = bake_with_threads(spec, 2);
  spec.with_z = false;
  const Texture rg = bake_with_threads(spec, 2);
  EXPECT_EQ(rg.channels, (std::vector<std::string>{"R", "G"}));
  EXPECT_EQ(rg.metadata.count("curl_scale_b"), 0u);
  EXPECT_EQ(rg.metadata.count("channel.B"), 0u);
  EXPECT_EQ(rg.metadata.at("curl_scale_rg"), rgb.metadata.at("curl_scale_rg"));
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 2; ++c) ASSERT_EQ(rg.at(x, y, 0, 0, c), rgb.at(x, y, 0, 0, c));
}

TEST(CurlTexture, ChannelsSpanTheUnitRangeAndTile) {
  const Texture t = bake_with_threads(CurlSpec{}, 2);
  float lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0};
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = t.at(x, y, 0, 0, c);
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
        lo[c] = std::min(lo[c], v);
        hi[c] = std::max(hi[c], v);
      }
  // The scale is an exact maximum: B, and R or G, touch 0 or 1.
  EXPECT_TRUE(lo[0] == 0 || hi[0] == 1 || lo[1] == 0 || hi[1] == 1);
  EXPECT_TRUE(lo[2] == 0 || hi[2] == 1);
  for (int c = 0; c < 3; ++c) {
    for (int axis = 0; axis < 2; ++axis) {
      float interior = 0, wrap = 0;
      for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
          const int nx = axis == 0 ? (x + 1) % 128 : x, ny = axis == 1 ? (y + 1) % 128 : y;
          const float d = std::abs(t.at(x, y, 0, 0, c) - t.at(nx, ny, 0, 0, c));
          float& slot = (axis == 0 ? x : y) == 127 ? wrap : interior;
          slot = std::max(slot, d);
        }
      // As in noise_volume_test: the wrapped face is one face among 128.
      EXPECT_LE(wrap, 1.1f * interior) << "channel " << c << " axis " << axis;
    }
  }
}

TEST(CurlTexture, BakedFieldIsNearlyDivergenceFree) {
  // Central differences on the texel grid (wrapping at the edges): for the
  // curl, d R / dx + d G / dy only holds the O(h^2) sampling error; the
  // control d R / dx - d G / dy is the same data combined without the
  // cancellation.
  const Texture t = bake_with_threads(CurlSpec{}, 2);
  double div = 0, control = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const int xp = (x + 1) % 128, xm = (x + 127) % 128, yp = (y + 1) % 128, ym = (y + 127) % 128;
      const double dr_dx = (t.at(xp, y, 0, 0, 0) - t.at(xm, y, 0, 0, 0)) / 2;
      const double dg_dy = (t.at(x, yp, 0, 0, 1) - t.at(x, ym, 0, 0, 1)) / 2;
      div += std::abs(dr_dx + dg_dy);
      control += std::abs(dr_dx - dg_dy);
    }
  EXPECT_LT(div / control, 0.1);
}

TEST(CurlTexture, SameDataForOneAndTwoThreadsAndSeedsDiffer) {
  const Texture two = bake_with_threads(CurlSpec{}, 2);
  const Texture one = bake_with_threads(CurlSpec{}, 1);
  EXPECT_TRUE(one.data == two.data);
  EXPECT_EQ(one.metadata, two.metadata);
  CurlSpec other;
  other.seed = 1;
  EXPECT_FALSE(bake_with_threads(other, 2).data == two.data);
}

TEST(CurlTexture, ChannelMeansStableAcrossSeeds) {
  // A signed field with zero mean encodes to ~0.5; the mean of 128^2 texels
  // over 4^2..16^2 lattice cells moves by ~0.2 / 4 = 0.05 at most.
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    CurlSpec spec;
    spec.seed = seed;
    const Texture t = bake_curl(spec, {});
    for (int c = 0; c < 3; ++c) {
      double mean = 0;
      for (size_t i = 0; i < t.texel_count(); ++i) mean += t.data[i * 3 + c];
      EXPECT_NEAR(mean / t.texel_count(), 0.5, 0.06) << "seed " << seed << " channel " << c;
    }
  }
}

TEST(CurlTexture, SpecProblems) {
  EXPECT_TRUE(spec_problems(CurlSpec{}).empty());
  CurlSpec spec;
  spec.octaves = 6;  // 4 * 32 = 128 > 64
  ASSERT_EQ(spec_problems(spec).size(), 1u);
  EXPECT_EQ(spec_problems(spec)[0].field, "octaves");
  EXPECT_THROW(bake_curl(spec, {}), Error);
  spec = {};
  spec.gain = 2.0f;
  EXPECT_EQ(spec_problems(spec)[0].field, "gain");
}

}  // namespace
}  // namespace skybake

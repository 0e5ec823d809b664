// The transmittance table's exponentials and node altitudes with the AVX2
// switch on and off (core/simd_switches.hpp): the same bits.
#include <cstring>

#include <gtest/gtest.h>

#include "atmosphere/transmittance_lut.hpp"
#include "core/simd_switches.hpp"
#include "support/test_atmospheres.hpp"
#include "support/wide_vectors_as.hpp"

namespace skybake {
namespace {

using test::WideVectorsAs;

bool same_bits(const Texture& a, const Texture& b) {
  return a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

// The transmittance table's exponentials and node altitudes four at a time
// (core/exp_block.hpp, transmittance_lut.cpp): the same bits.
TEST(Avx2Bakes, TransmittanceHasTheSameBitsInAvx2AndSse2) {
  {
    const WideVectorsAs probe(true);
    if (!avx2_enabled()) GTEST_SKIP() << "this CPU has no AVX2: only the SSE2 loops run";
  }
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const TransmittanceLutSpec spec{64, 16, 6};
    Texture sse2, avx2;
    {
      const WideVectorsAs as(false);
      sse2 = bake_transmittance_lut(atm, spec, BakeContext{});
    }
    {
      const WideVectorsAs as(true);
      avx2 = bake_transmittance_lut(atm, spec, BakeContext{});
    }
    EXPECT_TRUE(same_bits(sse2, avx2)) << "top radius " << atm.top_radius_m;
  }
}

TEST(Avx2Bakes, OffStaysOffAndOnFollowsTheCpu) {
  const WideVectorsAs off(false);
  EXPECT_FALSE(avx2_enabled());
  set_avx2_enabled(true);
  const bool on = avx2_enabled();
  set_avx2_enabled(false);
  EXPECT_FALSE(avx2_enabled());
  set_avx2_enabled(true);
  EXPECT_EQ(avx2_enabled(), on);
}

}  // namespace
}  // namespace skybake

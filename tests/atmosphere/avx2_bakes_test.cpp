// The AVX2 loops of the 4D orders (the density's Mie loop, the mu_s taps
// and the row blends of the multiple-scattering pass) against their SSE2
// twins, the Mie loop's AVX-512 twin against both, and the transmittance
// table's exponentials: the same bits (core/simd_switches.hpp).
// Sizes that leave remainders for every loop: 15 texels per row (nu 3 x
// mu_s 5), 25 direction pairs (5 zenith bands) padded to 32.
#include <cstring>

#include <gtest/gtest.h>

#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/simd_switches.hpp"
#include "support/test_atmospheres.hpp"
#include "support/test_scattering_specs.hpp"
#include "support/wide_vectors_as.hpp"

namespace skybake {
namespace {

using test::WideVectorsAs;
using test::WidestVectorsAs;

BrunetonTextures bake(const Atmosphere& atm, const Texture& lut, bool wide, int bands = 5) {
  const WideVectorsAs as(wide);
  BrunetonSpec spec = fixtures::small_bruneton_spec({6, 16, 5, 3, kBrunetonMuSMin}, 3);
  spec.density_directions = bands;
  return bake_bruneton(atm, lut, spec, BakeContext{});
}

bool same_bits(const Texture& a, const Texture& b) {
  return a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

TEST(Avx2Bakes, OrdersHaveTheSameBitsInAvx2AndSse2) {
  {
    const WideVectorsAs probe(true);
    if (!avx2_enabled()) GTEST_SKIP() << "this CPU has no AVX2: only the SSE2 loops run";
  }
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 40}, BakeContext{});
  const BrunetonTextures sse2 = bake(atm, lut, false), avx2 = bake(atm, lut, true);
  EXPECT_TRUE(same_bits(sse2.scattering, avx2.scattering));
  EXPECT_TRUE(same_bits(sse2.single_mie, avx2.single_mie));
  EXPECT_TRUE(same_bits(sse2.irradiance, avx2.irradiance));
  EXPECT_EQ(sse2.residuals, avx2.residuals);
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

// The density's Mie loop in AVX-512 (sixteen pairs per step) against AVX2
// and SSE2: the whole small bake, bit for bit, with 5 zenith bands (25 pairs
// padded to 32) and 6 (36 pairs padded to 40: a last group of 8, masked).
TEST(Avx2Bakes, OrdersHaveTheSameBitsInAvx512AndAvx2) {
  {
    const WideVectorsAs wide(true);
    const WidestVectorsAs probe(true);
    if (!avx512_enabled()) GTEST_SKIP() << "this CPU has no AVX-512: only AVX2 and SSE2 run";
  }
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 40}, BakeContext{});
  for (int bands : {5, 6}) {
    BrunetonTextures avx512, avx2;
    {
      const WidestVectorsAs as(true);
      avx512 = bake(atm, lut, true, bands);
    }
    {
      const WidestVectorsAs as(false);
      avx2 = bake(atm, lut, true, bands);
    }
    const BrunetonTextures sse2 = bake(atm, lut, false, bands);
    const BrunetonTextures* const others[] = {&avx2, &sse2};
    for (const BrunetonTextures* other : others) {
      EXPECT_TRUE(same_bits(avx512.scattering, other->scattering)) << bands << " bands";
      EXPECT_TRUE(same_bits(avx512.single_mie, other->single_mie));
      EXPECT_TRUE(same_bits(avx512.irradiance, other->irradiance));
      EXPECT_EQ(avx512.residuals, other->residuals);
    }
  }
}

TEST(Avx2Bakes, WidestNeedsWideAndFollowsTheCpu) {
  const WidestVectorsAs widest(true);
  const WideVectorsAs off(false);
  EXPECT_FALSE(avx512_enabled());  // AVX-512 only with the AVX2 loops on
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

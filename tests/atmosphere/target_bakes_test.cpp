// The transmittance table's bake, whose quadrature takes its exponentials
// and node altitudes over lanes (core/kernels/exp_block.hpp,
// atmosphere/kernels/node_altitudes.hpp), on each SIMD target this CPU
// runs against the scalar target: the same bits.
#include <cstring>

#include <gtest/gtest.h>

#include "atmosphere/transmittance_lut.hpp"
#include "support/simd_targets.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

bool same_bits(const Texture& a, const Texture& b) {
  return a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

Texture transmittance_on(int64_t target, const Atmosphere& atm) {
  const test::SimdTargetAs as(target);
  return bake_transmittance_lut(atm, TransmittanceLutSpec{64, 16, 6}, BakeContext{});
}

TEST(TargetBakes, TransmittanceIsTheSameOnEveryTarget) {
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const Texture scalar = transmittance_on(HWY_SCALAR, atm);
    for (int64_t target : hwy::SupportedAndGeneratedTargets())
      EXPECT_TRUE(same_bits(scalar, transmittance_on(target, atm)))
          << "top radius " << atm.top_radius_m << " " << hwy::TargetName(target);
  }
}

}  // namespace
}  // namespace skybake

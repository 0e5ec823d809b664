// The sky references' reads four points at a time (atmosphere/kernels/sun_and_psi_ms_reads.hpp)
// against the one-value lookups, and the block march that uses them with the
// AVX2 loops on and off: the same bits (core/simd_switches.hpp).
#include "atmosphere/kernels/sun_and_psi_ms_reads.hpp"

#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/simd_switches.hpp"
#include "support/test_atmospheres.hpp"
#include "support/wide_vectors_as.hpp"

namespace skybake {
namespace {

using test::WideVectorsAs;

bool same_bits(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

// Earth, the tiny planet and Earth under 1000x Rayleigh (the stiff extreme
// case, whose tables underflow near the ground).
std::vector<Atmosphere> atmospheres() {
  Atmosphere dense = fixtures::earth_atmosphere();
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  return {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense};
}

bool avx2_runs() {
  const WideVectorsAs probe(true);
  return avx2_enabled();
}

TEST(SunAndPsiMsReads, FourAtATimeAreTheOneValueLookupsBitForBit) {
  if (!avx2_runs()) GTEST_SKIP() << "this CPU has no AVX2: only the one-value reads run";
  for (const Atmosphere& atm : atmospheres()) {
    const Texture t = bake_transmittance_lut(atm, {64, 32, 16}, {});
    MultiscatteringLutSpec terminator{12, 10, 16, 12};
    terminator.sun_mapping = SunMapping::terminator;
    terminator.altitude_mapping = AltitudeMapping::quadratic;
    for (const MultiscatteringLutSpec& spec : {MultiscatteringLutSpec{12, 10, 16, 12}, terminator}) {
      const Texture ms = bake_multiscattering_lut(atm, t, spec, {});
      const MultiscatteringMapping mapping = multiscattering_mapping_of(ms);
      // Radii below the ground to above the top, sun cosines past [-1, 1],
      // dense around the horizon; 4 k + 3 points, so the last group is short.
      const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
      std::vector<double> r, mu_s;
      for (int i = 0; i < 23; ++i)
        for (int j = 0; j < 41; ++j) {
          r.push_back(rb - 10.0 + (rt - rb + 30.0) * std::pow(i / 22.0, 2.0));
          const double x = -1.0 + 2.0 * j / 40.0;
          mu_s.push_back(1.1 * x * std::abs(x));
        }
      const size_t n = r.size();
      for (const Texture* msp : {&ms, static_cast<const Texture*>(nullptr)}) {
        std::vector<glm::dvec3> sun_wide(n), ms_wide(n, glm::dvec3(-1.0)), sun_one(n),
            ms_one(n, glm::dvec3(-1.0));
        {
          const WideVectorsAs as(true);
          read_sun_and_psi_ms(atm, t, msp, mapping, r.data(), mu_s.data(), n, sun_wide.data(), ms_wide.data());
        }
        {
          const WideVectorsAs as(false);
          read_sun_and_psi_ms(atm, t, msp, mapping, r.data(), mu_s.data(), n, sun_one.data(), ms_one.data());
        }
        EXPECT_TRUE(same_bits(sun_wide, sun_one));
        EXPECT_TRUE(same_bits(ms_wide, ms_one));  // untouched (-1) without a table
        size_t lit = 0, shadowed = 0;
        for (size_t k = 0; k < n; ++k) {
          ASSERT_EQ(sun_one[k], lookup_sun_transmittance(t, atm, r[k], mu_s[k])) << k;
          if (msp) {
            ASSERT_EQ(ms_one[k], lookup_multiscattering(ms, mapping, atm, r[k], mu_s[k]));
          }
          (sun_one[k] == glm::dvec3(0.0) ? shadowed : lit) += 1;
        }
        EXPECT_GT(lit, n / 4);  // both sides of the horizon are read
        EXPECT_GT(shadowed, n / 20);
      }
    }
  }
}

TEST(SunAndPsiMsReads, BlockMarchHasTheSameBitsWithAndWithoutAvx2) {
  // The references' march (block exponentials, the sources read at the
  // midpoints or at the ends) with the AVX2 reads and without: ground and
  // space viewers, lit and shadowed, cut at the shadow and plain.
  if (!avx2_runs()) GTEST_SKIP() << "this CPU has no AVX2: only the one-value loops run";
  for (const Atmosphere& atm : atmospheres()) {
    const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb + 0.01 * (rt - rb), rb + 0.5 * (rt - rb), 1.5 * rt})
      for (double elevation : {-0.9, -0.05, 0.02, 0.4, 1.4})
        for (double sun_elevation : {-0.1, 0.05, 0.8})
          for (bool at_ends : {false, true}) {
            IntegrationOptions options;
            options.cut_at_shadow = !at_ends;
            options.distribution = at_ends ? StepDistribution::uniform : StepDistribution::quadratic;
            options.block_exponentials = true;
            options.sources_at_ends = at_ends;
            options.lit_ground = true;
            const glm::dvec3 p(0.0, 0.0, r);
            const glm::dvec3 dir(std::cos(elevation), 0.0, std::sin(elevation));
            const glm::dvec3 sun(std::cos(sun_elevation) * 0.6, std::cos(sun_elevation) * 0.8,
                                 std::sin(sun_elevation));
            const auto march = [&](bool wide) {
              const WideVectorsAs as(wide);
              return integrate_scattered_luminance(atm, l.transmittance, &l.multiscattering, p,
                                                   dir, sun, INFINITY, 41, options);
            };
            const ScatteringResult one = march(false), avx2 = march(true);
            ASSERT_EQ(avx2.luminance, one.luminance) << r << " " << elevation << " " << at_ends;
            ASSERT_EQ(avx2.transmittance, one.transmittance);
          }
  }
}

}  // namespace
}  // namespace skybake

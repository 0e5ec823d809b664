// The kernels of the error records' references on every SIMD target
// against the one-value functions, bit for bit: the multiple-scattering
// record's ring sums (verify/kernels/ring_sun_sums.hpp) against
// transmittance_at_radius, then lookup_sun_transmittance per azimuth.
#include "verify/kernels/ring_sun_sums.hpp"

#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/simd_targets.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

TEST_P(KernelsOnEachTarget, RingSunSumsAreTheOneValueSums) {
  Atmosphere dense = fixtures::earth_atmosphere();  // the stiff extreme case: reads underflow
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense}) {
    const Texture lut = bake_transmittance_lut(atm, {64, 32, 16}, {});
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    // Samples from the ground to past the top (clamped), at distances along
    // rays from points at several heights, suns on both sides of the
    // horizon; 4 k + 3 samples, so the last group of 2 or 4 lanes is short.
    const size_t n = 203;
    std::vector<double> radii(n), distances(n), inverse(n);
    for (size_t i = 0; i < n; ++i) {
      radii[i] = rb + (rt - rb) * 1.02 * std::pow(double(i) / (n - 1), 2.0);
      distances[i] = (rt - rb) * 3.0 * std::fmod(0.618 * double(i), 1.0);
      inverse[i] = 1.0 / radii[i];
    }
    size_t lit = 0, dark = 0;
    for (double r0 : {rb + 10.0, rb + 0.3 * (rt - rb), rt})
      for (double mu_s : {-0.4, -0.02, 0.1, 0.9}) {
        const double cosines[4] = {0.92 * mu_s - 0.3, 0.38 * mu_s + 0.1, -0.38 * mu_s, -0.92 * mu_s};
        const double height = r0 * mu_s;
        std::vector<glm::dvec3> wide_sums(n, glm::dvec3(-1.0)), one(n);
        ring_sun_sums(lut, atm, radii.data(), distances.data(), inverse.data(), n, height,
                      cosines, 4, wide_sums.data());
        for (size_t i = 0; i < n; ++i) {
          const TransmittanceAtRadius at = transmittance_at_radius(lut, atm, radii[i]);
          glm::dvec3 sum(0.0);
          for (double c : cosines) {
            const glm::dvec3 t =
                lookup_sun_transmittance(lut, at, rb, (height + distances[i] * c) * inverse[i]);
            sum += t;
            (t == glm::dvec3(0.0) ? dark : lit) += 1;
          }
          one[i] = sum;
        }
        EXPECT_EQ(std::memcmp(one.data(), wide_sums.data(), n * sizeof(one[0])), 0)
            << r0 << " " << mu_s;
      }
    EXPECT_GT(lit, 1000u);  // both sides of the horizon are summed
    EXPECT_GT(dark, 100u);
  }
}

SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET();

}  // namespace
}  // namespace skybake

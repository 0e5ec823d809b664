// SunSharedRay (atmosphere/sky_ray_suns.hpp): one ray marched once and read
// for many suns gives the per-ray march's luminance (integrate_scattered_luminance,
// uniform segments, no shadow cuts) to rounding, for single scattering,
// with an isotropic Psi_ms table and with one by view, and its sunlit
// ground is the march's lit ground.
#include <gtest/gtest.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/sky_ray_suns.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

void expect_close(glm::dvec3 a, glm::dvec3 b, const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], 1e-12 * std::max(std::abs(b[c]), 1e-30)) << what << " channel " << c;
}

std::vector<glm::dvec3> suns() {
  std::vector<glm::dvec3> out;
  for (double zenith_deg : {0.0, 30.0, 75.0, 89.0, 93.0, 100.0, 107.0}) {
    const double z = zenith_deg * kDeg;
    out.push_back({std::sin(z), 0.0, std::cos(z)});
  }
  return out;
}

std::vector<glm::dvec3> rays() {
  return {glm::normalize(glm::dvec3(0.3, 0.2, 0.9)), glm::normalize(glm::dvec3(-0.8, 0.1, 0.05)),
          glm::normalize(glm::dvec3(0.6, -0.5, -0.2)), glm::dvec3(0.0, 0.0, 1.0)};
}

void check_table(const Atmosphere& atm, const Texture& t, const Texture* ms) {
  for (double altitude : {0.0, 3000.0, 40000.0}) {
    const glm::dvec3 position(0.0, 0.0, atm.bottom_radius_m + altitude);
    for (const glm::dvec3& d : rays()) {
      MultiscatteringMapping mapping{};
      if (ms) mapping = multiscattering_mapping_of(*ms);
      const SunSharedRay ray(atm, t, ms, ms ? &mapping : nullptr, position, d, 24);
      for (const glm::dvec3& sun : suns()) {
        IntegrationOptions lit;
        lit.lit_ground = true;
        const ScatteringResult march =
            integrate_scattered_luminance(atm, t, ms, position, d, sun, INFINITY, 24, {});
        const ScatteringResult ground =
            integrate_scattered_luminance(atm, t, ms, position, d, sun, INFINITY, 24, lit);
        expect_close(ray.scattered(sun), march.luminance, "scattered");
        expect_close(ray.scattered(sun) + ray.sunlit_ground(sun),
                     ground.luminance, "with the lit ground");
        expect_close(ray.transmittance(), march.transmittance, "transmittance");
      }
    }
  }
}

TEST(SunSharedRay, SingleScatteringIsThePerRayMarch) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const fixtures::SkyLutInputs luts = fixtures::bake_sky_lut_inputs(atm);
  check_table(atm, luts.transmittance, nullptr);
}

TEST(SunSharedRay, IsotropicPsiMsIsThePerRayMarch) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const fixtures::SkyLutInputs luts = fixtures::bake_sky_lut_inputs(atm);
  check_table(atm, luts.transmittance, &luts.multiscattering);
}

TEST(SunSharedRay, PsiMsByViewIsThePerRayMarch) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const fixtures::SkyLutInputs luts = fixtures::bake_sky_lut_inputs(atm);
  ConvergedMultiscatteringSpec c;
  c.bruneton.r_size = 4;
  c.bruneton.mu_size = 16;
  c.bruneton.mu_s_size = 8;
  c.bruneton.nu_size = 4;
  c.bruneton.tolerance = 0.05;
  c.bands = 4;
  c.nu_slices = 4;
  c.zenith_slices = 4;
  MultiscatteringLutSpec table;
  table.width = 8;
  table.height = 8;
  table.sun_mapping = SunMapping::terminator;
  const ConvergedField field = compute_converged_field(atm, luts.transmittance, c, {});
  const Texture ms =
      converged_multiscattering_table(atm, luts.transmittance, table, c, field, {});
  ASSERT_GT(ms.layers * ms.depth, 1);  // the view slices are there
  check_table(atm, luts.transmittance, &ms);
}

}  // namespace
}  // namespace skybake

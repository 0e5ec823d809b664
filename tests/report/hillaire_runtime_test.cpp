// Hillaire's run-time as the report transcribes it (report/hillaire_march.hpp):
// with many samples his march of single scattering converges to the
// integral skybake's march converges to, reading the same transmittance
// (his in his layout, skybake's in its own), so the transcription's
// sampling, reads, phases and shadow are those of the sky it renders (his
// samples sit at their segments' far ends, a first-order error). Viewers
// stand 500 m up: his planet's-shadow test raises the planet by 10 m
// (PLANET_RADIUS_OFFSET), so samples in the lowest 10 m are in shadow, and
// a viewer at 1 m loses up to 0.4 % of its single scattering to that. And
// the quick section runs and judges its targets.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/preset_loader.hpp"
#include "report/hillaire_march.hpp"
#include "report/hillaire_runtime.hpp"
#include "report/sections.hpp"
#include "support/run.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(HillaireMarch, ManySamplesConvergeToSkybakesMarchOfTheSameTable) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {256, 64, 6}, {});
  TransmittanceLutSpec ts{256, 64, 6};
  ts.convention = TableConvention::hillaire_demo;
  const Texture t_demo = bake_transmittance_lut(atm, ts, {});
  DemoMarch fine;
  fine.variable = false;
  fine.min_samples = 40000.0;
  double worst = 0.0;
  for (double alt : {500.0, 10e3}) {
    const glm::dvec3 pos(0.0, 0.0, atm.bottom_radius_m + alt);
    for (double sun_deg : {60.0, 10.0})
      for (double e_deg : {5.0, 30.0, 80.0})
        for (double az : {0.3, 2.0}) {
          const double e = e_deg * kDeg, s = sun_deg * kDeg;
          const glm::dvec3 dir(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e));
          const glm::dvec3 sun(std::cos(s), 0.0, std::sin(s));
          const glm::dvec3 his =
              demo_integrate(atm, {&t_demo, nullptr}, pos, dir, sun, fine).luminance;
          const glm::dvec3 ours =
              integrate_scattered_luminance(atm, t, nullptr, pos, dir, sun, INFINITY, 40000).luminance;
          for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(his[c] / ours[c] - 1.0));
        }
  }
  std::printf("his march (40000 samples) against skybake's (40000 segments): worst %.3g\n", worst);
  EXPECT_LT(worst, 1e-3);
}

TEST(HillaireRuntimeSection, QuickRunJudgesItsTargets) {
  const Scene scene = load_scene(test::source_path("presets/earth.json"));
  const nlohmann::json settings = level_settings(true);
  const ReportLevel level = settings.get<ReportLevel>();
  const Atmosphere& atm = scene.atmosphere;
  const Texture t = bake_transmittance_lut(atm, TransmittanceLutSpec{}, {});
  const Texture ms = bake_multiscattering_lut(atm, t, MultiscatteringLutSpec{}, {});
  const nlohmann::json report = nlohmann::json::object();
  const ReportInputs in{scene, level, t, ms, t, report, test::test_dir("hillaire_runtime"), {}};
  const nlohmann::json out = hillaire_runtime_report(in, settings.get<HillaireRuntimeSetup>());
  ASSERT_EQ(out["targets"].size(), 6u);
  for (const char* m : {"march_30_31", "march_4_14", "march_2000", "march_30_31_midpoint",
                        "march_4_14_midpoint", "skyview_lookup"})
    for (const char* set : {"his_tables", "skybake_paper", "skybake_converged", "skybake_fitted"}) {
      const double v = out[m][set]["worst"]["rel_rmse"];
      EXPECT_TRUE(std::isfinite(v)) << m << " " << set;
      EXPECT_LT(v, 0.5) << m << " " << set;  // 64 paths: noisy, but the sky's size
    }
  for (const char* layout : {"full_circle_192x108", "half_circle_192x108", "full_circle_48x108",
                             "half_circle_48x108"}) {
    const double v = out["skyview_layouts"][layout]["worst"]["rel_rmse"];
    EXPECT_TRUE(std::isfinite(v)) << layout;
    EXPECT_LT(v, 0.5) << layout;
  }
}

}  // namespace
}  // namespace skybake

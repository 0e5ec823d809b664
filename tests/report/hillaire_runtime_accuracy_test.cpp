// The targets of the report section "Hillaire's runtime with skybake's
// tables" (report/hillaire_runtime.hpp) on Earth, at the section's full
// setting (240 views, 8192 paths; about a minute on 2 cores): Hillaire's
// demo run-time reading skybake's converged tables in his layout against
// the path tracer, beside his own tables. Prints every figure of the
// section (R/G/B denoised relative RMSE, max, bias).
//
// Measured: his sky-view read of the converged tables is 1.4/1.5/1.8 %
// against his own tables' 6.5/4.9/4.6 %, and his march at 2000 samples
// 1.5/1.6/1.9 % against 1.9/2.8/4.5 %: the tables are truer. His march as
// shipped samples each segment at 0.3 of its length, which at 30-31
// samples biases the sky by +2 to +4 % with exact tables (his own tables,
// 1 to 3.5 % dark, hide it): there the converged tables give 4.2 % worst
// against his tables' 3.8 %, and at 4-14 samples 7.8 % against 6.5 %; the
// targets asked of that march are not met. At the midpoint (0.5) his
// march reads the converged tables within 1.4/1.5/1.8 % at 30-31 samples
// and 1.4/1.4/1.7 % at 4-14. His march as shipped reading the converged
// Psi_ms fitted to it (fit_demo_march) gives 2.9 % at 30-31 and 4.6 % at
// 4-14: both targets met.
// The test holds what was met.
#include <gtest/gtest.h>

#include <cstdio>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "report/hillaire_runtime.hpp"
#include "report/sections.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

void print_row(const char* what, const nlohmann::json& stats) {
  std::printf("  %-20s", what);
  for (const auto& c : stats["channels"])
    std::printf(" %s %.2f%% (max %.0f%%)", c["channel"].get<std::string>().c_str(),
                100.0 * c["rel_rmse_denoised"].get<double>(), 100.0 * c["max_rel"].get<double>());
  std::printf("  bias");
  for (const auto& c : stats["channels"]) std::printf(" %+.2f%%", 100.0 * c["rel_bias"].get<double>());
  std::printf("  noise %.2f%%\n", 100.0 * stats["worst"]["noise_rel_rms"].get<double>());
}

TEST(HillaireRuntimeAccuracy, TargetsOnEarth) {
  const Scene scene = load_scene(test::source_path("presets/earth.json"));
  const nlohmann::json settings = level_settings(false);
  const ReportLevel level = settings.get<ReportLevel>();
  const Atmosphere& atm = scene.atmosphere;
  const Texture t = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  const Texture ms = bake_multiscattering_lut(
      atm, t, multiscattering_spec(operating_spec(scene, "multiscattering")), BakeContext{});
  const nlohmann::json report = nlohmann::json::object();
  const ReportInputs in{scene, level, t, ms, t, report, test::test_dir("hillaire_runtime"), {}};
  const nlohmann::json out = hillaire_runtime_report(in, settings.get<HillaireRuntimeSetup>());
  std::printf("%zu views, %d paths\n", out["views"].get<size_t>(),
              out["path_tracer"]["samples"].get<int>());
  for (const char* m : {"march_30_31", "march_4_14", "march_2000", "march_30_31_midpoint", "march_4_14_midpoint", "skyview_lookup"}) {
    std::printf("%s\n", m);
    for (const char* set : {"his_tables", "skybake_paper", "skybake_converged", "skybake_fitted"})
      print_row(set, out[m][set]);
  }
  std::printf("skyview_layouts (skybake's converged sky-view)\n");
  for (const auto& [layout, stats] : out["skyview_layouts"].items()) print_row(layout.c_str(), stats);
  for (const auto& cam : out["by_camera_altitude"]) {
    std::printf("camera at %g m (worst channel):", cam["altitude_m"].get<double>());
    for (const char* m : {"march_30_31", "march_4_14", "march_2000", "march_30_31_midpoint", "march_4_14_midpoint", "skyview_lookup"})
      for (const char* set : {"his_tables", "skybake_paper", "skybake_converged", "skybake_fitted"})
        std::printf(" %s/%s %.2f%%", m, set,
                    100.0 * cam["worst"][m][set]["rel_rmse_denoised"].get<double>());
    std::printf("\n");
  }
  for (const auto& target : out["targets"]) {
    std::printf("target: %s: %.2f%% against %.2f%%: %s\n", target["what"].get<std::string>().c_str(),
                100.0 * target["value"].get<double>(), 100.0 * target["limit"].get<double>(),
                target["status"].get<std::string>().c_str());
  }
  // The sky-view read, the midpoint march and his march as shipped reading
  // the Psi_ms fitted to it meet theirs.
  EXPECT_EQ(out["targets"][2]["status"], "met");
  EXPECT_EQ(out["targets"][3]["status"], "met");
  EXPECT_EQ(out["targets"][4]["status"], "met");
  EXPECT_EQ(out["targets"][5]["status"], "met");
  // With his march's own error out of the way, skybake's tables are the truer.
  const auto worst = [&](const char* m, const char* set) {
    return out[m][set]["worst"]["rel_rmse_denoised"].get<double>();
  };
  EXPECT_LT(worst("march_2000", "skybake_converged"), worst("march_2000", "his_tables"));
}

}  // namespace
}  // namespace skybake

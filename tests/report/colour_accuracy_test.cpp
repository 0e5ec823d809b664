// The report section "Colour" (report/colour.hpp) on earth_spectral
// (Bruneton's demo constants) at full size: the tables' spectral sampling
// alone, N = 15 and three wavelengths against a 120-wavelength table
// sampled uniformly over 360-830 nm. The
// comparison with the spectral path tracer at the section's full setting is
// the report's (`skybake report presets/earth_spectral.json --only skyview`,
// docs/report.md "Colour"); the unit twin is colour_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>

#include "pipeline/preset_loader.hpp"
#include "report/colour.hpp"
#include "report/sections.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

// The spectral sampling error alone, tables against the 120-wavelength
// uniform table at full size (a few path-tracer samples: the reference is
// not read by these figures). Targets: N = 15 within Delta u'v' 0.002 and
// 1% of the luminance on every view, the sun 6 degrees down included.
TEST(ColourAccuracy, SpectralSamplingOfTheTablesOnEarth) {
  const Scene scene = load_scene(test::source_path("presets/earth_spectral.json"));
  const nlohmann::json settings = level_settings(false);
  ColourSetup setup = settings.get<ColourSetup>();
  setup.colour_samples = 4;
  setup.colour_wavelengths = {15, 120};
  setup.colour_reference_wavelengths = 120;
  const ReportLevel level = settings.get<ReportLevel>();
  const Texture none;
  const nlohmann::json report = nlohmann::json::object();
  const std::filesystem::path dir = test::test_dir("colour_sampling");
  const ReportInputs in{scene, level, none, none, none, report, dir, {}};
  const nlohmann::json out = colour_report(in, setup);
  std::printf("%-9s %-6s | rgb3 duv dY      | n15 duv dY\n", "altitude", "sun");
  for (const auto& v : out["views"]) {
    std::printf("%7.0f m %5.0f ", v["altitude_m"].get<double>(), v["sun_elevation_deg"].get<double>());
    for (const char* t : {"rgb3", "n15"})
      std::printf(" | %.4f %6.2f%%", v[t]["table_delta_uv"].get<double>(),
                  100.0 * v[t]["table_luminance_error"].get<double>());
    std::printf("\n");
  }
  ASSERT_EQ(out["views"].size(), 12u);
  for (const auto& v : out["views"]) {
    EXPECT_LE(v["n15"]["table_delta_uv"].get<double>(), 0.002) << v.dump();
    EXPECT_LE(v["n15"]["table_luminance_error"].get<double>(), 0.01) << v.dump();
    // Three wavelengths are farther on every view.
    EXPECT_GT(v["rgb3"]["table_delta_uv"].get<double>(), v["n15"]["table_delta_uv"].get<double>());
  }
}

}  // namespace
}  // namespace skybake

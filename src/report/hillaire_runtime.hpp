// Report section "Hillaire's runtime with skybake's tables" (docs/report.md):
// the run-time of Hillaire's public demo (atmosphere/hillaire_demo_march.hpp,
// report/hillaire_march.hpp: his ray march and his sky-view read,
// transcribed) renders sky views with four sets of tables, against the path
// tracer (reference/path_tracer.hpp):
//   his_tables          the tables his demo makes each frame (his passes:
//                       transmittance with 40 far-end samples, Psi_ms from
//                       8 x 8 directions, the sky-view from his march);
//   skybake_paper       skybake's transmittance and Psi_ms (Hillaire 2020's
//                       model) and sky-view, in his layout ("convention":
//                       "hillaire_demo");
//   skybake_converged   the same with the converged Psi_ms ("model":
//                       "converged");
//   skybake_fitted      the converged Psi_ms fitted to his march
//                       ("fit_demo_march", atmosphere/hillaire_demo_march_fit.hpp),
//                       its sky-view his own pass reading it.
// Each set is rendered by his ray march at his two sample-count settings
// (RayMarchMinMaxSPP 30-31 and the demo's default 4-14), by the same march
// at 2000 samples (the tables' share of the error without the march's own)
// and at both settings with each sample at its segment's midpoint
// (SampleSegmentT 0.5 for his 0.3), and by his sky-view read; also per
// camera altitude (worst channels). skyview_layouts: skybake's converged
// sky-view in the full circle and his half circle, at 192 x 108 and 48 x 108.
// Views: cameras at 1 m and 10 km, suns 60, 10 and 2 degrees up,
// view_elevations x view_azimuths directions each; statistics as in the
// sky-radiance section (radiance_stats, sky_radiance.hpp).
//
// Targets (Earth): ray march at 30-31 with the converged tables below his own
// tables' worst channel; at 4-14 no worse than his own + 0.5 points; his
// sky-view read at most half of his own tables' figure; the midpoint march
// at 30-31 with the converged tables below his own tables in his march as
// shipped; and the first two with the fitted Psi_ms.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct HillaireRuntimeSetup {
  // (Prefixed: the level settings hold every section's keys side by side.)
  std::vector<double> hillaire_camera_altitudes_m;
  std::vector<double> hillaire_sun_elevations_deg;
  std::vector<double> hillaire_view_elevations_deg;
  int hillaire_view_azimuths = 8;
  int hillaire_path_samples = 0;  // paths per channel and view

  static HillaireRuntimeSetup quick();
  static HillaireRuntimeSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(HillaireRuntimeSetup, hillaire_camera_altitudes_m,
                                   hillaire_sun_elevations_deg, hillaire_view_elevations_deg,
                                   hillaire_view_azimuths, hillaire_path_samples)

nlohmann::json hillaire_runtime_report(const ReportInputs& in, const HillaireRuntimeSetup& setup);

}  // namespace skybake

// Hillaire's multiple-scattering approximation against Bruneton's
// precomputed scattering orders, both against the path tracer, on the views,
// sun elevations and camera of the sky radiance section
// (sky_radiance.hpp), on any scene: Earth, Mars, the tiny planet and a dense
// atmosphere are the cases docs/report.md discusses.
//
// Bruneton side: the scene's own `scattering` output when it has one (its
// shape, orders or tolerance, Mie storage), else the level's table (full:
// the default 32x128x32x8 shape iterated until an order changes the table by
// less than 1e-3, at most 100 orders, 32x128x64x16 where the Mie group
// shapes the multiple scattering, orders_resolution.hpp; quick: 16x64x16x4,
// 4 orders), baked
// from the operating-point transmittance table. Each view is read the way an
// engine reads the table: lookup_scattering at the camera's (r, mu, mu_s, nu),
// single Mie from the alpha channel when the table is combined.
//
// Output: {"status": "measured", "bruneton": {what was baked, orders used,
// last residual, seconds}, "hillaire": sky_radiance "multiple",
// "bruneton_vs_path_tracer": radiance statistics, "bruneton_by_sun": [...],
// "bruneton_exact_mie_vs_path_tracer": the same table read with single Mie
// from its own texture instead of the alpha channel's extrapolation (equal
// to the above when the table stores Mie separately),
// "skyview_single_plus_bruneton_multiple_vs_path_tracer": the sky-view
// layer's single scattering (Psi_ms = 0) plus the table's orders >= 2 (the
// table minus its own single-scattering tables, same taps), the daytime
// target judged on each (target_json): "target", "exact_mie_target",
// "hybrid_target",
// "views": [{sun, elevation, azimuth, "bruneton": RGB,
// "skyview_single_plus_bruneton_multiple": RGB}]}, or
// {"status": "not run", "reason"} when there is no sky radiance section.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

// Bruneton's tables when the scene has no scattering output of its own:
// shape (r, mu, mu_s, nu) and orders, or with tolerance > 0 orders until the
// residual drops below it; bruneton_shape_mie_lobe instead of bruneton_shape
// where mie_shapes_multiple_scattering (empty: never).
struct BrunetonSetup {
  std::vector<int> bruneton_shape;
  std::vector<int> bruneton_shape_mie_lobe;
  int bruneton_orders = 4;
  double bruneton_tolerance = 0.0;
  int bruneton_max_orders = 100;

  static BrunetonSetup quick();
  static BrunetonSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(BrunetonSetup, bruneton_shape, bruneton_shape_mie_lobe,
                                   bruneton_orders,
                                   bruneton_tolerance, bruneton_max_orders)

// Reads the report's "sky_radiance" (its views and path-traced references
// are reused); "not run" when that section was not run.
nlohmann::json bruneton_comparison_report(const ReportInputs& in, const BrunetonSetup& setup);

}  // namespace skybake

// `skybake report`: how exact every product of a scene is, and at what cost
// (docs/report.md). For each atmosphere table the scene requests, a ladder of
// sample counts and resolutions measured against independent references with
// the run time of each bake (ladders.hpp); the sky's radiance rendered
// from the tables against a path tracer (sky_radiance.hpp); where
// float32 and half storage lose (precision.hpp and each product's
// half round trip); sky previews. Noise and cloud products are exact
// evaluations of their functions and are listed as such.
//
// Writes DIR/<scene>/report/report.json, report.html (self-contained but for
// the preview PNG beside it, html.hpp) and sky_preview.png, each
// atomically. Never fails on accuracy: the numbers are reported, not judged;
// errors (a product the scene does not request, an unwritable folder) throw.
// Nothing else of DIR/<scene>/ is touched (no manifest, no baked outputs).
//
// report.json: {"tool", "scene", "preset", "level", "level_settings",
//   "seconds", "products": [per product, ladders.hpp or
//   {"product", "kind": "exact" | "preview" | "section" | "not_measured", "note"}],
//   "sky_radiance": sky_radiance.hpp or null,
//   "precision": {"horizon_transmittance": precision.hpp or null,
//                 "half": [{"product", "float", "half", "storage"}]},
//   "bruneton_comparison": {"status", ...}, "files": {...}}
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

struct ReportOptions {
  std::filesystem::path out_dir = "out";
  std::vector<std::string> products;  // empty: every product the scene requests
  bool quick = false;                 // ReportLevel::quick() instead of full()
  int path_samples = 0;               // > 0: paths per view for every order (else the level's)
  ReportStage on_stage;               // progress messages; may be empty
};

struct ReportResult {
  std::filesystem::path folder;  // DIR/<scene>/report
  nlohmann::json report;         // the contents of report.json
};

// Throws UsageError when --only names a product the scene does not
// request (with "did you mean"), IoError when a file cannot be written.
ReportResult run_report(const Scene& scene, const ReportOptions& options);

// The headline numbers of a report (for --json and the summary table): per
// product the operating point's settings, seconds, max_rel, rms_rel and its
// half max_rel; the sky radiance's worst-channel relative RMSE and target.
nlohmann::json report_summary(const ReportResult& result);

}  // namespace skybake

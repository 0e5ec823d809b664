// Error against run time of the atmosphere LUTs (`skybake report`, docs/report.md):
// each product is baked at a ladder of sample counts and resolutions, every
// bake is timed, and every table is read the way an engine reads it (its
// lookup_* function, interpolation included) at a fixed set of
// pseudo-random query points and compared with a reference computed
// independently of the table:
//   transmittance       adaptive quadrature (reference_transmittance_to_top)
//   multiscattering     the same integral with many more directions and steps
//   skyview             the same march with many more steps (same input LUTs),
//                       and for single scattering the adaptive quadrature
//                       (reference_single_scattering), independent of every LUT
//   aerial_perspective  the same march with many more steps (same input LUTs)
//   scattering          single scattering (one order) against adaptive
//                       quadrature (reference_single_scattering); the orders
//                       >= 2 are in the Bruneton comparison (path tracer)
//   single_mie          the separate single-Mie texture against adaptive
//                       quadrature of the Mie group's phase-free single
//                       scattering
//   irradiance          one order: direct sunlight against adaptive quadrature
//                       of the transmittance, indirect against a nested
//                       adaptive hemisphere integral of that quadrature
//   scattering3d        one order against the azimuth mean of the phase-free
//                       quadrature (what an azimuth-free texel can hold), and
//                       beside it against the radiance at the query's azimuth
//   gathering_sum       the preset's orders against a finer bake
//                       (self-convergence)
// The preset's own settings are the operating point (added to the ladder
// when the grid lacks them); the Pareto front is over (seconds, max_rel).
// Each product also measures its operating-point table stored as half.
//
// Output, per product (report.json "products"):
//   {"product", "kind": "lut", "reference", "queries",
//    "axes": {settings key: the values the ladder takes},
//    "ladder": [{"label", "settings", "seconds", "samples", "max_abs",
//                "max_rel", "rms_rel", "operating_point", "pareto", ...}],
//    "operating_point": index, "pareto": [indices by rising cost],
//    "half": {"float": stats, "half": stats, "storage": half_storage_stats}}
#pragma once

#include <cstdint>
#include <functional>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"
#include "verify/query_points.hpp"

namespace skybake {

// Each ladder's setup and entry point is in its own header (transmittance.hpp,
// ...); these tools are what they share.

// Bakes and measures one ladder point: returns an object with at least
// "seconds" and the ErrorStats fields (max_abs, max_rel, rms_rel, samples).
using LadderMeasure = std::function<nlohmann::json(const nlohmann::json& settings)>;

// Runs `measure` over `grid` plus the operating point (appended when no grid
// point has equal settings) and returns {"axes", "ladder", "operating_point",
// "pareto"}; each point gets "label", "settings", "operating_point" and
// "pareto". Reports a stage per point.
nlohmann::json run_ladder(const std::string& product, const nlohmann::json& axes,
                          const std::vector<nlohmann::json>& grid, const nlohmann::json& operating,
                          const LadderMeasure& measure, const ReportInputs& in);

// "size=256x64 steps=40"
std::string settings_label(const nlohmann::json& settings);

}  // namespace skybake

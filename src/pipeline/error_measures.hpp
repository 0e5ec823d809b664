// The error every bake records for its atmosphere tables (manifest "error",
// docs/decisions/error-records.md): each table is
// read the way an engine reads it, its lookup_* function with the
// interpolation, at deterministic off-texel query points
// (verify/query_points.hpp: the first n of the points `skybake report`
// uses), against a reference that does not use the table: a converged
// integration of the same quantity at those points. These are the report's
// ladders at their operating point with fewer queries and references that
// stay in the bake's layers (no adaptive quadrature, no path tracer), so the
// two agree within a factor of 2 on every shipped preset
// (tests/report/bake_error_test.cpp) at a few percent of the bake's time.
//
// The precomputed-scattering tables are measured on their single-scattering
// order, as the report's ladders are: the same shape and ray quadrature baked
// with one order (the "twin", cached per process and family), read as the
// table is read, against single scattering integrated without a table.
// Orders >= 2 have no reference a bake can afford (the report compares them
// with the path tracer).
//
// The noise volumes and the curl texture record the tiling verdict of
// `check-tiling` (core/tiling.hpp) instead.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <nlohmann/json.hpp>

#include "core/error_stats.hpp"
#include "pipeline/product.hpp"

namespace skybake {

// The value read from the table and the reference of each query, RGB.
using QueryReads = std::vector<std::pair<glm::dvec3, glm::dvec3>>;

// Manifest "error": {"rms_rel", "max_rel", "queries", "reference"}, relative
// errors over every query and colour channel with the floor of ErrorTally.
nlohmann::json error_record(const QueryReads& reads, const std::string& reference);

// RGB S_R with S_M.r in alpha (Bodare & Sandberg eq. 19): how a table with
// "mie": "alpha" stores its single-scattering order.
Texture with_mie_in_alpha(const Texture& rayleigh, const Texture& mie);

// The single-scattering order of a precomputed family's table (4D or 3D),
// stored as the family's table stores it: RGB S_R, + A = S_M.r when Mie is in
// alpha, else S_M apart.
struct FirstOrder {
  Texture table;
  Texture separate_mie;  // empty when Mie is in alpha
};

template <class Family>
FirstOrder first_order(const Family& family) {
  if (family.scattering.channel_count() >= 4)
    return {with_mie_in_alpha(family.single_rayleigh, family.single_mie), Texture()};
  return {family.single_rayleigh, family.single_mie};
}

// One per atmosphere table (MeasureFn of product.hpp).
nlohmann::json measure_transmittance_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                           const Texture&);
nlohmann::json measure_multiscattering_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                             const Texture&);
nlohmann::json measure_skyview_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                     const Texture&);
nlohmann::json measure_aerial_perspective_error(const Scene&, const OutputSpec&,
                                                const ProductInputs&, const Texture&);
nlohmann::json measure_scattering_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                        const Texture&);
nlohmann::json measure_single_mie_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                        const Texture&);
nlohmann::json measure_irradiance_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                        const Texture&);
nlohmann::json measure_scattering3d_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                          const Texture&);
nlohmann::json measure_gathering_sum_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                           const Texture&);

// Manifest "tiling" of a tileable texture: {"verdict", "tiles",
// "worst_ratio", "tolerance", "statistic"}, measure_tiling of level 0 at
// check-tiling's default tolerance (cli/commands.hpp CheckTilingArgs).
constexpr double kTilingTolerance = 0.25;
nlohmann::json tiling_record(const Texture& texture);

}  // namespace skybake

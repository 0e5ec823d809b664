// What a bake warns about (docs/decisions/warnings.md): the one place that
// decides, from a baked texture, its metadata and its measured error or
// tiling record, whether an output is worth a warning. A warning has a
// stable code, a message with its numbers, and the numbers themselves:
//   not_converged      orders stopped at max_orders above the tolerance
//   tail_dominates     the geometric tail stands for much of the table
//   fms_clamped        f_ms of multiple scattering reached 1 and was clamped
//   energy_gain        a 4D table returns more light than the sun gives
//   coarse_table       a 4D table's second order between mu texels is far
//                      from its quadrature
//   black_output       every colour texel is 0 though the medium scatters
//   transmittance_underflow  transmittance texels that float32 holds as 0
//   error_above_limit  the measured max_rel is above max_error (or the
//                      product's default)
//   not_tileable       a noise texture's seam stands out (check-tiling)
// They go to stderr, `bake --json` and the manifest entry; `bake --strict`
// exits 1 on any.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/texture.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

struct OutputWarning {
  std::string code;
  std::string message;  // the numbers, for people
  nlohmann::json numbers = nlohmann::json::object();
  nlohmann::json json() const;  // {"code", "message", ...numbers}
};

// tail_dominates: the geometric tail's share of a texel, bounded by
// max_c f_c x the last residual, above this.
constexpr double kMaxTailShare = 0.1;

// The warnings of one baked output. `error` and `tiling` are the records of
// error_measures.hpp (null when the product has none).
std::vector<OutputWarning> output_warnings(const Scene& scene, const OutputSpec& spec,
                                           const Texture& texture, const nlohmann::json& error,
                                           const nlohmann::json& tiling);

// "code: message" of a manifest warning, for the one line on stderr.
std::string warning_line(const nlohmann::json& warning);

}  // namespace skybake

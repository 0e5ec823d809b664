// The records of error_measures.hpp: what the manifest keeps of a measurement.
#include <cmath>

#include "core/tiling.hpp"
#include "pipeline/error_measures.hpp"

namespace skybake {

nlohmann::json error_record(const QueryReads& reads, const std::string& reference) {
  ErrorTally tally;
  for (const auto& [value, ref] : reads)
    for (int c = 0; c < 3; ++c) tally.add(value[c], ref[c]);
  const ErrorStats stats = tally.stats();
  return {{"rms_rel", stats.rms_rel},
          {"max_rel", stats.max_rel},
          {"queries", reads.size()},
          {"reference", reference}};
}

Texture with_mie_in_alpha(const Texture& rayleigh, const Texture& mie) {
  Texture out(rayleigh.width, rayleigh.height, rayleigh.depth, 1, {"R", "G", "B", "A"});
  for (size_t t = 0; t < rayleigh.texel_count(); ++t) {
    for (int c = 0; c < 3; ++c) out.data[4 * t + c] = rayleigh.data[3 * t + c];
    out.data[4 * t + 3] = mie.data[3 * t];
  }
  return out;
}

nlohmann::json tiling_record(const Texture& texture) {
  const TilingReport report = measure_tiling(texture, kTilingTolerance);
  return {{"verdict", tiling_verdict_name(report.verdict)},
          {"tiles", report.tiles},
          {"worst_ratio", std::isfinite(report.worst_ratio) ? nlohmann::json(report.worst_ratio)
                                                            : nlohmann::json()},
          {"tolerance", kTilingTolerance},
          {"statistic",
           "check-tiling's (core/tiling.hpp): per axis and channel, the seam's jump and turn "
           "of slope against the distribution of the interior faces', level 0"}};
}

}  // namespace skybake

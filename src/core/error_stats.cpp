#include "core/error_stats.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

nlohmann::json ErrorStats::json() const {
  return {{"samples", samples}, {"max_abs", max_abs}, {"max_rel", max_rel}, {"rms_rel", rms_rel}};
}

void ErrorTally::add(const ErrorTally& other) {
  pairs_.insert(pairs_.end(), other.pairs_.begin(), other.pairs_.end());
}

ErrorStats ErrorTally::stats(double floor_fraction) const {
  double scale = 0.0;
  for (const auto& [v, r] : pairs_) scale = std::max(scale, std::abs(r));
  const double floor = std::max(floor_fraction * scale, 1e-30);
  ErrorStats s;
  s.samples = pairs_.size();
  double sum_sq = 0.0;
  for (const auto& [v, r] : pairs_) {
    const double abs_err = std::abs(v - r);
    const double rel = abs_err / std::max(std::abs(r), floor);
    s.max_abs = std::max(s.max_abs, abs_err);
    s.max_rel = std::max(s.max_rel, rel);
    sum_sq += rel * rel;
  }
  s.rms_rel = std::sqrt(sum_sq / double(std::max<size_t>(pairs_.size(), 1)));
  return s;
}

double query_unit(uint64_t index, uint32_t dim) {
  uint64_t z = index * 0x9E3779B97F4A7C15ull + (uint64_t(dim) + 1) * 0xD1B54A32D192ED03ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-53;
}

}  // namespace skybake

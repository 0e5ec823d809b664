// Error statistics against a reference and the deterministic query points
// they are measured at, shared by the bake's error measurement
// (pipeline/error_measures.hpp) and `skybake report` (report/stats.hpp), so
// that both read a table at the same points and summarize it the same way.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace skybake {

// Relative error of a value against its reference, with a floor on the
// denominator so that values that are nearly black (transmittance through a
// dense horizon, a sky-view layer at night) do not dominate:
//   rel = |value - ref| / max(|ref|, floor_fraction * max |ref| over the set).
struct ErrorStats {
  size_t samples = 0;
  double max_abs = 0.0;  // largest |value - ref|, units of the quantity
  double max_rel = 0.0;  // largest rel
  double rms_rel = 0.0;  // sqrt(mean rel^2)
  nlohmann::json json() const;
};

constexpr double kRelativeFloor = 1e-3;

class ErrorTally {
 public:
  void add(double value, double reference) { pairs_.push_back({value, reference}); }
  void add(const ErrorTally& other);
  ErrorStats stats(double floor_fraction = kRelativeFloor) const;
  size_t size() const { return pairs_.size(); }

 private:
  std::vector<std::pair<double, double>> pairs_;
};

// A deterministic pseudo-random number in [0, 1) for query `index` and
// coordinate `dim` (a hash, splitmix64: no shared generator state, so the
// query set is the same for any thread count and any run).
double query_unit(uint64_t index, uint32_t dim);

}  // namespace skybake

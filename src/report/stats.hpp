// Small tools shared by the sections of `skybake report` (report/report.hpp):
// error statistics against a reference, deterministic pseudo-random query
// points, wall-clock timing of a bake, the Pareto front of a ladder, and the
// half-float round trip of a table.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/texture.hpp"

namespace skybake {

// Relative error of a value against its reference, with a floor on the
// denominator so that values that are nearly black (transmittance through a
// dense horizon, a sky-view layer at night) do not dominate:
//   rel = |value - ref| / max(|ref|, floor_fraction * max |ref| over the set).
// The same convention as the manifest's estimated errors (error_estimates.hpp).
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

// Mean wall seconds of one call of `bake`: repeated until at least
// min_seconds in total have passed (at most max_runs times), because the
// smallest tables bake in microseconds, below the clock's useful resolution.
// Returns the last result through `out`.
template <typename F, typename T>
double time_bake(F&& bake, T& out, double min_seconds, int max_runs = 64) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  int runs = 0;
  double elapsed = 0.0;
  do {
    out = bake();
    ++runs;
    elapsed = std::chrono::duration<double>(clock::now() - t0).count();
  } while (elapsed < min_seconds && runs < max_runs);
  return elapsed / runs;
}

// Indices of the points on the Pareto front of (cost, error), both to be
// minimised: a point is on the front when no other point is at least as good
// in both and better in one. Sorted by cost.
std::vector<size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error);

// Marks each ladder point of `ladder` (an array of objects with "seconds" and
// "max_rel") with "pareto": true/false and returns the indices on the front.
std::vector<size_t> mark_pareto(nlohmann::json& ladder);

// The texture stored as IEEE binary16 and read back (core/half.hpp): what an
// engine sees when the table is shipped as half.
Texture half_round_trip(const Texture& tex);

// What half storage does to a table's texels: how many non-zero values
// flush to 0, how many land in half's subnormal range (below 2^-14, where
// the relative precision degrades), how many overflow to infinity, and the
// largest relative round-trip error of the other texels.
nlohmann::json half_storage_stats(const Texture& tex);

}  // namespace skybake

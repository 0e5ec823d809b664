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

#include "core/error_stats.hpp"
#include "core/texture.hpp"

namespace skybake {

// ErrorStats, ErrorTally and query_unit are core/error_stats.hpp's: the bake
// measures its tables with the same statistics at the same points.

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

#include "report/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/half.hpp"

namespace skybake {

std::vector<size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error) {
  std::vector<size_t> order(cost_error.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return cost_error[a] < cost_error[b];  // by cost, then by error
  });
  // Sweep by rising cost: a point is on the front when its error is below
  // every cheaper point's.
  std::vector<size_t> front;
  double best = INFINITY;
  for (size_t i : order)
    if (cost_error[i].second < best) {
      front.push_back(i);
      best = cost_error[i].second;
    }
  return front;
}

std::vector<size_t> mark_pareto(nlohmann::json& ladder) {
  std::vector<std::pair<double, double>> points;
  for (const auto& p : ladder) points.push_back({p["seconds"], p["max_rel"]});
  const std::vector<size_t> front = pareto_front(points);
  for (auto& p : ladder) p["pareto"] = false;
  for (size_t i : front) ladder[i]["pareto"] = true;
  return front;
}

Texture half_round_trip(const Texture& tex) {
  Texture out = tex;
  for (float& v : out.data) v = float_from_half(half_from_float(v));
  return out;
}

nlohmann::json half_storage_stats(const Texture& tex) {
  constexpr float kSmallestNormalHalf = 6.103515625e-05f;  // 2^-14
  size_t flushed = 0, subnormal = 0, overflow = 0;
  double max_rel = 0.0;
  for (float v : tex.data) {
    const float h = float_from_half(half_from_float(v));
    if (v != 0.0f && h == 0.0f) {
      ++flushed;
    } else if (std::isinf(h)) {
      ++overflow;
    } else if (v != 0.0f && std::abs(v) < kSmallestNormalHalf) {
      ++subnormal;
    } else if (v != 0.0f) {
      max_rel = std::max(max_rel, double(std::abs(h - v)) / std::abs(v));
    }
  }
  return {{"values", tex.data.size()},
          {"flushed_to_zero", flushed},
          {"subnormal", subnormal},
          {"overflow", overflow},
          {"max_rel_round_trip_normal", max_rel}};
}

}  // namespace skybake

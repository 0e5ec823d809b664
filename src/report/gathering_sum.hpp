// Gathering sum (the 3D family's, the preset's orders) ladder of `skybake
// report` (gathering_sum.cpp): shapes (h, mu, mu_s) x gathering directions,
// against one finer bake (self-convergence).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct GatheringSumSetup {
  std::vector<std::vector<int>> gathering_shapes;
  std::vector<int> gathering_directions;
  int gathering_queries = 0;
  std::vector<int> gathering_reference_shape;
  int gathering_reference_directions = 0;
  int gathering_reference_ray_nodes = 0;

  static GatheringSumSetup quick();
  static GatheringSumSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(GatheringSumSetup, gathering_shapes, gathering_directions,
                                   gathering_queries, gathering_reference_shape,
                                   gathering_reference_directions, gathering_reference_ray_nodes)

nlohmann::json gathering_sum_report(const ReportInputs& in, const GatheringSumSetup& setup);

}  // namespace skybake

// Scattering (Bruneton 4D, single scattering) ladder of `skybake report`
// (scattering.cpp): shapes (r, mu, mu_s, nu) x ray nodes, against adaptive
// quadrature.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct ScatteringSetup {
  std::vector<std::vector<int>> scattering_shapes;
  std::vector<int> scattering_ray_nodes;
  int scattering_queries = 0;

  static ScatteringSetup quick();
  static ScatteringSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ScatteringSetup, scattering_shapes, scattering_ray_nodes,
                                   scattering_queries)

nlohmann::json scattering_report(const ReportInputs& in, const ScatteringSetup& setup);

}  // namespace skybake

// Single Mie (the 4D family's separate texture, one order) ladder of `skybake
// report` (single_mie.cpp): shapes (r, mu, mu_s, nu) x ray nodes, against
// adaptive quadrature of the Mie group's phase-free single scattering.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct SingleMieSetup {
  std::vector<std::vector<int>> single_mie_shapes;
  std::vector<int> single_mie_ray_nodes;
  int single_mie_queries = 0;

  static SingleMieSetup quick();
  static SingleMieSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SingleMieSetup, single_mie_shapes, single_mie_ray_nodes,
                                   single_mie_queries)

nlohmann::json single_mie_report(const ReportInputs& in, const SingleMieSetup& setup);

}  // namespace skybake

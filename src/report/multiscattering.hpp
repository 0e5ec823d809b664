// Multiple-scattering ladder of `skybake report` (multiscattering.cpp):
// directions x steps x sizes; the reference is the same integral with many more
// directions and steps.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct MultiscatteringSetup {
  std::vector<int> multiscattering_directions;
  std::vector<std::vector<int>> multiscattering_sizes;  // empty: the preset's size only
  std::vector<int> multiscattering_steps;
  int multiscattering_queries = 0;
  int multiscattering_reference_directions = 0;
  int multiscattering_reference_steps = 0;

  static MultiscatteringSetup quick();
  static MultiscatteringSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(MultiscatteringSetup, multiscattering_directions,
                                   multiscattering_sizes, multiscattering_steps,
                                   multiscattering_queries, multiscattering_reference_directions,
                                   multiscattering_reference_steps)

nlohmann::json multiscattering_report(const ReportInputs& in, const MultiscatteringSetup& setup);

}  // namespace skybake

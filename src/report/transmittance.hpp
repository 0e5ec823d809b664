// Transmittance ladder of `skybake report` (transmittance.cpp): steps x sizes,
// each table against adaptive quadrature of the optical depth.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct TransmittanceSetup {
  std::vector<int> transmittance_steps;
  std::vector<std::vector<int>> transmittance_sizes;
  int transmittance_queries = 0;

  static TransmittanceSetup quick();
  static TransmittanceSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TransmittanceSetup, transmittance_steps, transmittance_sizes,
                                   transmittance_queries)

nlohmann::json transmittance_report(const ReportInputs& in, const TransmittanceSetup& setup);

}  // namespace skybake

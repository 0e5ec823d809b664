// Irradiance (the 4D family's ground irradiance, one order) ladder of `skybake
// report` (irradiance.cpp): sizes (mu_s, r) x hemisphere directions, read from
// a 4D table of the preset's scattering shape; the reference integrates
// adaptive quadrature of single scattering over the hemisphere.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct IrradianceSetup {
  std::vector<std::vector<int>> irradiance_sizes;
  std::vector<int> irradiance_directions;
  int irradiance_queries = 0;
  double irradiance_reference_tolerance = 1e-4;  // relative, of the hemisphere integral

  static IrradianceSetup quick();
  static IrradianceSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(IrradianceSetup, irradiance_sizes, irradiance_directions,
                                   irradiance_queries, irradiance_reference_tolerance)

nlohmann::json irradiance_report(const ReportInputs& in, const IrradianceSetup& setup);

}  // namespace skybake

// Sky-view ladder of `skybake report` (skyview.cpp): steps x sizes over the
// preset's layers; the reference is the same march with many more steps, and
// for single scattering the adaptive quadrature.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct SkyviewSetup {
  std::vector<int> skyview_steps;
  std::vector<std::vector<int>> skyview_sizes;
  int skyview_queries = 0;
  int skyview_reference_steps = 0;

  static SkyviewSetup quick();
  static SkyviewSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SkyviewSetup, skyview_steps, skyview_sizes, skyview_queries,
                                   skyview_reference_steps)

nlohmann::json skyview_report(const ReportInputs& in, const SkyviewSetup& setup);

}  // namespace skybake

// Aerial-perspective ladder of `skybake report` (aerial_perspective.cpp):
// steps_per_slice x slice counts; the reference is the same march with many
// uniform steps.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct AerialPerspectiveSetup {
  std::vector<int> aerial_steps;   // steps per slice
  std::vector<int> aerial_depths;  // slice counts
  int aerial_queries = 0;
  int aerial_reference_steps = 0;

  static AerialPerspectiveSetup quick();
  static AerialPerspectiveSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(AerialPerspectiveSetup, aerial_steps, aerial_depths,
                                   aerial_queries, aerial_reference_steps)

nlohmann::json aerial_perspective_report(const ReportInputs& in,
                                         const AerialPerspectiveSetup& setup);

}  // namespace skybake

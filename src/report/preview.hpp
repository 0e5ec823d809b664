// The sky preview of `skybake report` (preview.cpp): pictures rendered from
// the operating-point tables, written as sky_preview.png beside report.json.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct PreviewSetup {
  std::vector<int> preview_size;  // width, height

  static PreviewSetup quick();
  static PreviewSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PreviewSetup, preview_size)

// Writes the picture into in.folder and returns its file name.
nlohmann::json sky_preview_report(const ReportInputs& in, const PreviewSetup& setup);

}  // namespace skybake

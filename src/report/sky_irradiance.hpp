// The sky_irradiance section of `skybake report` (sky_irradiance.cpp): the
// table at the preset's settings against the path tracer's E(n), with its
// three errors apart: the decode at texels, L2's own limit, and the
// bilinear read between texels (docs/runtime.md "Sky irradiance").
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct SkyIrradianceReportSetup {
  std::vector<int> sky_irradiance_rows;     // altitude texel rows measured
  std::vector<int> sky_irradiance_columns;  // sun zenith texel columns (daylight)
  std::vector<int> sky_irradiance_twilight_columns;  // columns past 90 degrees
  int sky_irradiance_normals = 64;
  int sky_irradiance_rays_below = 4, sky_irradiance_rays_above = 8;
  int sky_irradiance_azimuths = 12;
  int sky_irradiance_samples = 32;  // paths per ray and channel
  // The same in twilight, where the light is faint and a few long paths
  // carry much of it: at 256 the blue 11 degrees down came out 16% low;
  // 1024 is within 1% of 4096 there (docs/report.md "Sky irradiance").
  int sky_irradiance_twilight_samples = 1024;

  static SkyIrradianceReportSetup quick();
  static SkyIrradianceReportSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SkyIrradianceReportSetup, sky_irradiance_rows,
                                   sky_irradiance_columns, sky_irradiance_twilight_columns,
                                   sky_irradiance_normals, sky_irradiance_rays_below,
                                   sky_irradiance_rays_above, sky_irradiance_azimuths,
                                   sky_irradiance_samples, sky_irradiance_twilight_samples)

nlohmann::json sky_irradiance_report(const ReportInputs& in, const SkyIrradianceReportSetup& setup);

}  // namespace skybake

// The "Colour" section of `skybake report` (docs/report.md): how far the
// colour and luminance of a sky baked at three wavelengths, and at N of them
// (docs/decisions/spectral-tables.md), are from the spectral path tracer
// (reference/spectral_path_tracer.hpp). Runs for a scene with "spectral".
//
// Views: a viewer at each of colour_altitudes_m under each of
// colour_sun_elevations_deg; in each, the sky-view texels at the zenith,
// at mid elevation and just above the horizon, toward the sun, across it
// and away from it (9 directions). Tables: the scene's transmittance and
// multiple-scattering outputs and a sky-view of colour_skyview_size with
// one layer per view, baked
// - at three wavelengths: the RGB coefficients (680, 550, 440 nm) with the
//   sun's true colour as the sun (what an RGB engine given the sun's colour
//   renders);
// - at each count of colour_wavelengths, group by group.
// The reference traces colour_reference_wavelengths with colour_samples
// paths per channel, group and direction.
// Per view and table: delta_uv, the largest CIE 1976 Delta u'v' over the
// directions, and luminance_error, the largest |Y / Y_ref - 1|; each with the
// reference's own noise propagated (ref_delta_uv_ci95, ref_luminance_ci95).
// Also table_delta_uv and table_luminance_error: each table against the
// reference count's table (the spectral sampling error without the tables'
// own). Targets: N = 15 within
// Delta u'v' 0.002 and luminance 1% on every view.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct ColourSetup {
  std::vector<int> colour_skyview_size;
  std::vector<int> colour_wavelengths;  // the spectral counts compared (3-wavelength RGB is always)
  int colour_reference_wavelengths = 42;
  int colour_samples = 0;  // paths per channel, group and direction
  std::vector<double> colour_sun_elevations_deg;
  std::vector<double> colour_altitudes_m;

  static ColourSetup quick();
  static ColourSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ColourSetup, colour_skyview_size, colour_wavelengths,
                                   colour_reference_wavelengths, colour_samples,
                                   colour_sun_elevations_deg, colour_altitudes_m)

nlohmann::json colour_report(const ReportInputs& in, const ColourSetup& setup);

// The section in report.html (colour_html.cpp).
std::string colour_html(const nlohmann::json& colour);

}  // namespace skybake

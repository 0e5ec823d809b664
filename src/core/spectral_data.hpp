// Tabulated physical spectra over the visible range, as published (the
// sources are listed in docs/reference.md, "Spectral data"):
// - the CIE 1931 2-degree colour-matching functions x_bar, y_bar, z_bar,
//   every 5 nm from 360 to 830 nm;
// - the sun's spectral irradiance at the top of the atmosphere (ASTM G-173
//   extraterrestrial column, averaged over 10 nm bins), W m^-2 nm^-1;
// - the ozone absorption cross-section at 233 K (Serdyuchenko et al. 2014,
//   averaged over 10 nm bins), m^2 per molecule.
// Between samples the tables are read by linear interpolation.
#pragma once

#include <glm/glm.hpp>

namespace skybake {

constexpr double kSpectrumMinNm = 360.0;
constexpr double kSpectrumMaxNm = 830.0;

// (x_bar, y_bar, z_bar) at `nm`; zero outside [360, 830] nm.
glm::dvec3 cie1931_xyz_bar(double nm);

// ASTM G-173 extraterrestrial spectral irradiance at `nm`, W m^-2 nm^-1;
// the end values beyond the table's range.
double astm_g173_solar_irradiance(double nm);

// Ozone absorption cross-section at 233 K at `nm`, m^2; the end values
// beyond the table's range.
double ozone_cross_section_m2(double nm);

// One Dobson unit: 2.687e20 molecules per m^2 of column.
constexpr double kDobsonUnitPerM2 = 2.687e20;

// Maximum luminous efficacy of radiation at 555 nm, lm/W (the SI candela).
constexpr double kMaxLuminousEfficacy = 683.0;

}  // namespace skybake

// Tests for core/colour.hpp, core/spectral_grid.hpp and core/spectral_data.hpp
// against closed forms: published matrices, white points, the equal-energy
// white of the CIE 1931 system, and the fine-step integral of a spectrum.
#include "core/colour.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/spectral_data.hpp"
#include "core/spectral_grid.hpp"

namespace skybake {
namespace {

TEST(Colour, Rec709MatrixMatchesTheSrgbStandard) {
  // IEC 61966-2-1 publishes XYZ -> linear sRGB to four decimals.
  const glm::dmat3 m = rgb_from_xyz(chromaticities_of(ColourSpace::rec709));
  const double published[3][3] = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) EXPECT_NEAR(m[col][row], published[row][col], 1e-3);
}

TEST(Colour, WhitePointIsRgbOne) {
  for (ColourSpace s : {ColourSpace::rec709, ColourSpace::acescg}) {
    const Chromaticities c = chromaticities_of(s);
    const glm::dvec3 white(c.white.x / c.white.y, 1.0, (1.0 - c.white.x - c.white.y) / c.white.y);
    const glm::dvec3 rgb = rgb_from_xyz(c) * white;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(rgb[i], 1.0, 1e-12) << colour_space_name(s);
    // The red primary maps to (1, 0, 0) up to its luminance.
    const glm::dvec3 red = rgb_from_xyz(c) * glm::dvec3(c.red.x / c.red.y, 1.0,
                                                         (1.0 - c.red.x - c.red.y) / c.red.y);
    EXPECT_NEAR(red.y, 0.0, 1e-12);
    EXPECT_NEAR(red.z, 0.0, 1e-12);
  }
}

TEST(Colour, UvPrimeOfEqualEnergyWhiteAndRoundTrip) {
  const glm::dvec2 e = uv_prime_from_xyz(glm::dvec3(1.0));
  EXPECT_NEAR(e.x, 4.0 / 19.0, 1e-15);
  EXPECT_NEAR(e.y, 9.0 / 19.0, 1e-15);
  const glm::dvec3 xyz(0.3, 0.5, 0.9);
  const glm::dvec3 back = xyz_from_uv_prime(uv_prime_from_xyz(xyz), xyz.y);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], xyz[i], 1e-14);
  EXPECT_EQ(uv_prime_from_xyz(glm::dvec3(0.0)), glm::dvec2(0.0));
}

TEST(SpectralData, ColourMatchingFunctionsInterpolate) {
  EXPECT_DOUBLE_EQ(cie1931_xyz_bar(555.0).y, 1.0);  // V(lambda) peaks at 555 nm
  EXPECT_NEAR(cie1931_xyz_bar(557.5).y, 0.5 * (1.0 + 0.995), 1e-12);
  EXPECT_EQ(cie1931_xyz_bar(359.0), glm::dvec3(0.0));
  EXPECT_EQ(cie1931_xyz_bar(831.0), glm::dvec3(0.0));
}

TEST(SpectralData, SolarIlluminanceIsTheKnownValue) {
  // The sun's illuminance at the top of Earth's atmosphere is about
  // 1.28e5 lux (1.2e5 to 1.35e5 by source and season).
  const glm::dvec3 xyz = spectrum_xyz(astm_g173_solar_irradiance);
  EXPECT_GT(xyz.y * kMaxLuminousEfficacy, 1.20e5);
  EXPECT_LT(xyz.y * kMaxLuminousEfficacy, 1.35e5);
}

TEST(SpectralData, OzoneChappuisBandPeaksNear600nm) {
  double best = 0.0, best_nm = 0.0;
  for (double nm = 400.0; nm <= 800.0; nm += 10.0)
    if (ozone_cross_section_m2(nm) > best) best = ozone_cross_section_m2(nm), best_nm = nm;
  EXPECT_GE(best_nm, 590.0);
  EXPECT_LE(best_nm, 610.0);
  EXPECT_NEAR(best, 5e-25, 0.5e-25);
}

TEST(SpectralGrid, GroupsAreBinMidpointsOverTheSampledRange) {
  const SpectralGrid g = spectral_grid(15);
  ASSERT_EQ(g.groups.size(), 5u);
  EXPECT_DOUBLE_EQ(g.step_nm, 300.0 / 15.0);
  EXPECT_DOUBLE_EQ(g.groups[0][0], 395.0 + 10.0);
  EXPECT_DOUBLE_EQ(g.groups[4][2], 695.0 - 10.0);
  EXPECT_EQ(spectral_grid(40).wavelength_count(), 42);
  // The bins tile the CIE range: the end bins reach 360 and 830 nm.
  EXPECT_EQ(g.bin(0, 0), glm::dvec2(360.0, 415.0));
  EXPECT_EQ(g.bin(2, 1), glm::dvec2(535.0, 555.0));
  EXPECT_EQ(g.bin(4, 2), glm::dvec2(675.0, 830.0));
  for (size_t i = 0; i < g.groups.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const bool last = i + 1 == g.groups.size() && k == 2;
      if (!last) EXPECT_DOUBLE_EQ(g.bin(i, k).y, g.bin(i + (k + 1) / 3, (k + 1) % 3).x);
    }
  // Uniform sampling: Bruneton's equal bins over the whole CIE range.
  const SpectralGrid u = spectral_grid(15, SpectralSampling::uniform);
  EXPECT_DOUBLE_EQ(u.step_nm, 470.0 / 15.0);
  EXPECT_DOUBLE_EQ(u.groups[0][0], 360.0 + 0.5 * 470.0 / 15.0);
  EXPECT_DOUBLE_EQ(u.groups[4][2], 830.0 - 0.5 * 470.0 / 15.0);
  EXPECT_NEAR(u.bin(0, 0).y - u.bin(0, 0).x, 470.0 / 15.0, 1e-9);
}

TEST(SpectralGrid, FlatSpectrumGivesTheEqualEnergyWhite) {
  // The CIE 1931 functions have equal integrals: a flat spectrum is the
  // system's white, illuminant E, at (x, y) = (1/3, 1/3), for any N (the
  // bins integrate the sun exactly).
  const SpectrumFn flat = [](double) { return 1.0; };
  for (SpectralSampling sampling : {SpectralSampling::visible, SpectralSampling::uniform})
    for (int n : {3, 15, 42}) {
      const glm::dvec2 xy = xy_from_xyz(grid_xyz(spectral_grid(n, sampling), flat, flat));
      EXPECT_NEAR(xy.x, 1.0 / 3.0, 2e-4) << n;
      EXPECT_NEAR(xy.y, 1.0 / 3.0, 2e-4) << n;
    }
  // The sum of every group's RGB matrix applied to a flat response under a
  // flat sun is the RGB of E.
  const SpectralGrid g = spectral_grid(15);
  const glm::dmat3 to_rgb = rgb_from_xyz(chromaticities_of(ColourSpace::rec709));
  glm::dvec3 rgb(0.0);
  for (size_t i = 0; i < g.groups.size(); ++i)
    rgb += group_colour_matrix(g, i, flat, to_rgb) * glm::dvec3(1.0);
  const glm::dvec3 e = to_rgb * spectrum_xyz(flat, 0.25);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rgb[i] / e[i], 1.0, 1e-4);
}

TEST(SpectralGrid, SunAtZeroAirMassIsTheSolarSpectrumsXyz) {
  // Transmittance 1 at every wavelength: the grid reproduces the sun's own
  // XYZ whatever the number of wavelengths.
  const glm::dvec3 fine = spectrum_xyz(astm_g173_solar_irradiance, 0.25);
  for (SpectralSampling sampling : {SpectralSampling::visible, SpectralSampling::uniform})
    for (int n : {3, 15, 42}) {
      const glm::dvec3 xyz = grid_xyz(spectral_grid(n, sampling), [](double) { return 1.0; },
                                      astm_g173_solar_irradiance);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(xyz[i] / fine[i], 1.0, 1e-4) << n;
    }
}

TEST(SpectralGrid, SmoothResponseConvergesWithTheWavelengthCount) {
  // Rayleigh's lambda^-4 through 30 air masses (a low sun): the grid's error
  // against the fine integral falls as N grows.
  const SpectrumFn reddened = [](double nm) { return std::exp(-0.35 * std::pow(nm / 550.0, -4.0)); };
  const glm::dvec3 fine = spectrum_xyz(
      [&](double nm) { return reddened(nm) * astm_g173_solar_irradiance(nm); }, 0.25);
  for (SpectralSampling sampling : {SpectralSampling::visible, SpectralSampling::uniform}) {
    double last = 1.0;
    for (int n : {6, 15, 42}) {
      const glm::dvec3 xyz =
          grid_xyz(spectral_grid(n, sampling), reddened, astm_g173_solar_irradiance);
      const glm::dvec2 d = uv_prime_from_xyz(xyz) - uv_prime_from_xyz(fine);
      const double err = std::hypot(d.x, d.y);
      EXPECT_LT(err, last) << n;
      last = err;
    }
    EXPECT_LT(last, 1e-4);
  }
}

}  // namespace
}  // namespace skybake

// Colour spaces and the CIE 1976 UCS, as pure functions.
// An RGB space is its primaries' and white point's chromaticities (the
// numbers OpenEXR's `chromaticities` attribute carries); its matrix to CIE
// XYZ follows from them (SMPTE RP 177): the columns are the primaries' XYZ,
// scaled so that RGB (1, 1, 1) is the white point at Y = 1.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace skybake {

enum class ColourSpace {
  rec709,  // linear sRGB: Rec. ITU-R BT.709 primaries, D65 white
  acescg,  // ACES AP1 primaries, ACES white (~D60), SMPTE ST 2065-1 / S-2014-004
};

struct Chromaticities {
  glm::dvec2 red, green, blue, white;  // CIE 1931 (x, y)
};

Chromaticities chromaticities_of(ColourSpace space);
// "rec709" or "acescg", the names presets and metadata use.
std::string colour_space_name(ColourSpace space);

// XYZ = M * RGB for a space of these chromaticities; and its inverse.
glm::dmat3 xyz_from_rgb(const Chromaticities& c);
glm::dmat3 rgb_from_xyz(const Chromaticities& c);

// CIE 1976 UCS: u' = 4X / (X + 15Y + 3Z), v' = 9Y / (X + 15Y + 3Z);
// (0, 0) for black.
glm::dvec2 uv_prime_from_xyz(const glm::dvec3& xyz);
// The XYZ of luminance Y at chromaticity (u', v').
glm::dvec3 xyz_from_uv_prime(const glm::dvec2& uv, double luminance);
// CIE 1931 (x, y) of an XYZ; (0, 0) for black.
glm::dvec2 xy_from_xyz(const glm::dvec3& xyz);

}  // namespace skybake

// Sky previews for artists: the sky rendered from the baked LUTs the way an
// engine uses them (sky_render.hpp: sky-view for the sky, transmittance for
// the sun disk, aerial perspective over the ground), one panel per sun
// elevation: high sun, 10 degrees, sunset, just below the horizon, and a view
// of the whole planet from space.
//
// Shape: width x height per panel, one layer per panel (a 2D array; the PNG
// writer lays layers side by side). Values are display-referred, in [0, 1]:
// each panel is exposed so its sky's 90th-percentile luminance maps to 0.8,
// then tone mapped with x / (1 + x) scaled so 1 stays 1 at the white point;
// the exposures are in the metadata (`exposure_<panel>`) so the physical
// luminance can be recovered. This is a picture to look at, not a LUT.
// Reads: transmittance, multiscattering (and bakes its own sky-view layer
// and aerial-perspective volume per panel, in memory).
#pragma once

#include <string>
#include <vector>

#include "atmosphere/medium.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyPreviewPanel {
  std::string label;         // "noon", "sun_10deg", ...
  double sun_elevation_deg;  // above the horizon
  bool from_space = false;   // camera far above, looking at the planet
};

struct SkyPreviewSpec {
  int width = 320;  // pixels per panel
  int height = 180;
  double camera_altitude_m = 200.0;  // ground views
  double camera_pitch_deg = 12.0;    // ground views look slightly up, toward the sun
  double vertical_fov_deg = 70.0;
  std::vector<SkyPreviewPanel> panels = {{"high_sun", 60.0, false},
                                         {"sun_10deg", 10.0, false},
                                         {"sunset", 0.0, false},
                                         {"below_horizon", -3.0, false},
                                         {"from_space", 30.0, true}};
};

Texture bake_sky_preview(const Atmosphere& atm, const Texture& transmittance_lut,
                         const Texture& multiscattering_lut, const SkyPreviewSpec& spec,
                         const BakeContext& ctx);

// The two halves of bake_sky_preview: the panels' linear radiance (RGB, one
// layer per panel; linear in the sun, so a spectral bake sums it over
// wavelength groups), and its exposure and tone mapping with the metadata.
Texture render_sky_preview_radiance(const Atmosphere& atm, const Texture& transmittance_lut,
                                    const Texture& multiscattering_lut,
                                    const SkyPreviewSpec& spec, const BakeContext& ctx);
Texture tone_map_sky_preview(const Texture& radiance, const Atmosphere& atm,
                             const SkyPreviewSpec& spec);

}  // namespace skybake

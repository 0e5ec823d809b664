#include "atmosphere/sky_preview.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/sky_render.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

constexpr double kWhite = 4.0;  // extended Reinhard white point (exposed units)

double luminance(const float* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// Exposure that maps the panel's 90th-percentile luminance to 0.8: robust to
// the sun disk, which covers far fewer than 10 % of the pixels.
double auto_exposure(const float* rgb, size_t texels) {
  std::vector<double> y(texels);
  for (size_t i = 0; i < y.size(); ++i) y[i] = luminance(&rgb[i * 3]);
  const size_t k = size_t(0.9 * double(y.size() - 1));
  std::nth_element(y.begin(), y.begin() + k, y.end());
  return y[k] > 0.0 ? 0.8 / y[k] : 1.0;
}

float tonemap(double x) {
  const double c = x * (1.0 + x / (kWhite * kWhite)) / (1.0 + x);
  return float(std::clamp(c, 0.0, 1.0));
}

// The camera's altitude of a panel: from space far enough that the whole
// planet and its atmosphere fit the frame; on the ground the spec's, at most
// half the atmosphere's depth.
double panel_altitude_m(const Atmosphere& atm, const SkyPreviewSpec& spec,
                        const SkyPreviewPanel& panel) {
  if (panel.from_space)
    return atm.top_radius_m / std::sin(0.45 * spec.vertical_fov_deg * kDeg) - atm.bottom_radius_m;
  return std::min(spec.camera_altitude_m, 0.5 * (atm.top_radius_m - atm.bottom_radius_m));
}

Texture render_panel(const Atmosphere& atm, const Texture& transmittance,
                     const Texture& multiscattering, const SkyPreviewSpec& spec,
                     const SkyPreviewPanel& panel) {
  const double sun_zenith = (90.0 - panel.sun_elevation_deg) * kDeg;
  SkyImageSpec image;
  image.width = spec.width;
  image.height = spec.height;
  image.camera.aspect = double(spec.width) / spec.height;
  image.camera.vertical_fov_rad = spec.vertical_fov_deg * kDeg;
  image.sun_zenith_rad = sun_zenith;
  image.sun_azimuth_rad = 0.0;
  SkyLuts luts;
  luts.transmittance = &transmittance;
  luts.multiscattering = &multiscattering;
  const BakeContext quiet;
  image.camera.altitude_m = panel_altitude_m(atm, spec, panel);
  if (panel.from_space) {
    image.camera.pitch_rad = -kPi / 2;
    return render_sky_image(atm, luts, image, quiet);
  }
  image.camera.pitch_rad = spec.camera_pitch_deg * kDeg;
  image.camera.yaw_rad = 0.0;  // toward the sun

  SkyviewLutSpec sky;
  sky.views = {{image.camera.altitude_m, sun_zenith}};
  const Texture skyview = bake_skyview_lut(atm, transmittance, multiscattering, sky, quiet);
  AerialPerspectiveSpec ap;
  ap.camera = image.camera;
  ap.sun_zenith_rad = sun_zenith;
  ap.depth_range_m = std::min(32e3, 2.0 * (atm.top_radius_m - atm.bottom_radius_m));
  const Texture aerial =
      bake_aerial_perspective_lut(atm, transmittance, multiscattering, ap, quiet);
  luts.skyview = &skyview;
  luts.skyview_layer = 0;
  luts.aerial_perspective = &aerial;
  luts.aerial_perspective_range_m = ap.depth_range_m;
  return render_sky_image(atm, luts, image, quiet);
}

}  // namespace

Texture render_sky_preview_radiance(const Atmosphere& atm, const Texture& transmittance,
                                    const Texture& multiscattering, const SkyPreviewSpec& spec,
                                    const BakeContext& ctx) {
  const int n = int(spec.panels.size());
  Texture out(spec.width, spec.height, 1, n, {"R", "G", "B"});
  const size_t panel_values = size_t(spec.width) * spec.height * 3;
  for (int p = 0; p < n; ++p) {
    const Texture hdr = render_panel(atm, transmittance, multiscattering, spec, spec.panels[p]);
    std::copy(hdr.data.begin(), hdr.data.begin() + panel_values,
              out.data.begin() + ptrdiff_t(size_t(p) * panel_values));
    ctx.report(size_t(p + 1), size_t(n));
  }
  return out;
}

Texture tone_map_sky_preview(const Texture& radiance, const Atmosphere& atm,
                             const SkyPreviewSpec& spec) {
  const int n = int(spec.panels.size());
  Texture out(spec.width, spec.height, 1, n, {"R", "G", "B"});
  const size_t panel_values = size_t(spec.width) * spec.height * 3;
  for (int p = 0; p < n; ++p) {
    const float* src = radiance.data.data() + size_t(p) * panel_values;
    const double exposure = auto_exposure(src, panel_values / 3);
    float* dst = out.data.data() + size_t(p) * panel_values;
    for (size_t i = 0; i < panel_values; ++i) dst[i] = tonemap(exposure * src[i]);
    set_meta(out.metadata, fmt::format("panel_{}", p), spec.panels[p].label);
    // What the PNG's label of the panel says (png_preview.hpp panel_labels).
    set_meta(out.metadata, fmt::format("panel_{}_sun_elevation_deg", p),
             spec.panels[p].sun_elevation_deg);
    set_meta(out.metadata, fmt::format("panel_{}_camera_altitude_m", p),
             panel_altitude_m(atm, spec, spec.panels[p]));
    set_meta(out.metadata, fmt::format("exposure_{}", p), exposure);
  }
  set_meta(out.metadata, "quantity",
           "display-referred sky preview in [0, 1]: luminance * exposure_<panel>, tone mapped "
           "x (1 + x / 16) / (1 + x)");
  return out;
}

Texture bake_sky_preview(const Atmosphere& atm, const Texture& transmittance,
                         const Texture& multiscattering, const SkyPreviewSpec& spec,
                         const BakeContext& ctx) {
  return tone_map_sky_preview(
      render_sky_preview_radiance(atm, transmittance, multiscattering, spec, ctx), atm, spec);
}

}  // namespace skybake

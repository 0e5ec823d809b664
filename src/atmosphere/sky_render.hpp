// Renders what a viewer sees from the baked LUTs, the way an engine uses them
// (Hillaire 2020 sections 5.3-5.4 and 7): the sky-view LUT for the sky, the
// transmittance LUT for the sun disk and the ground seen through the
// atmosphere, the aerial-perspective LUT over the ground when one was baked
// for the same camera. Views with no matching sky-view layer (from space, or
// none given) ray march instead (section 7: "we seamlessly switch to simple
// ray marching"). For previews and error reports; nothing here is baked
// into a product.
//
// Frames: positions are planet-centred (m); view_dir travels away from the
// eye, sun_dir points toward the sun (sky_integrator.hpp). Results are
// luminance in units of Atmosphere::sun_illuminance.
//
// The ground is a diffuse sphere of albedo Atmosphere::ground_albedo lit by
// the sun only (albedo / pi E T_sun max(mu_s, 0); no sky irradiance), the
// sun a uniform disk of angular radius Atmosphere::sun_angular_radius_rad and
// luminance E / (2 pi (1 - cos(radius))), attenuated by the transmittance
// to the top (docs/reference.md "Sun disk and previews": the solid angle of a
// disk, Hillaire 2016 eq. 14).
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/medium.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyLuts {
  const Texture* transmittance = nullptr;    // required
  const Texture* multiscattering = nullptr;  // for ray-marched views; null = single scattering
  const Texture* skyview = nullptr;          // null: ray march every view
  int skyview_layer = 0;                     // the layer baked for this altitude and sun zenith
  // Aerial perspective baked for the camera of the image (render_sky_image only).
  const Texture* aerial_perspective = nullptr;
  double aerial_perspective_range_m = 32e3;  // its depth_range_m
};

struct SkyRenderOptions {
  bool sun_disk = true;  // composite the sun disk
  bool ground = true;    // shade the ground where the view ray meets it
  int march_steps = 32;  // segments per ray when ray marching
};

// Luminance of the sun disk toward view_dir from position_m: 0 outside the
// disk and when the ground hides it, else E / solid angle * T(view to top).
glm::dvec3 lookup_sun_disk_luminance(const Atmosphere& atm, const Texture& transmittance_lut,
                                     glm::dvec3 position_m, glm::dvec3 view_dir,
                                     glm::dvec3 sun_dir);

// Luminance toward view_dir: sky (sky-view LUT when given and the viewer is
// inside the atmosphere, else the ray march), the ground and the sun disk.
// Pure; thread-safe.
glm::dvec3 render_sky_luminance(const Atmosphere& atm, const SkyLuts& luts, glm::dvec3 position_m,
                                glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                const SkyRenderOptions& options = {});

struct SkyImageSpec {
  int width = 320;
  int height = 180;
  SkyCamera camera;  // aspect should be width / height
  double sun_zenith_rad = kPi / 4;
  double sun_azimuth_rad = 0.0;
  SkyRenderOptions options;
};

// A perspective image (channels R, G, B; row 0 at the top) through
// render_sky_luminance per pixel centre. Where the ground is hit within the
// aerial-perspective range and luts.aerial_perspective is set, the ground is
// shaded as an engine would: ground * A + RGB of the froxel.
// Rows in parallel; deterministic.
Texture render_sky_image(const Atmosphere& atm, const SkyLuts& luts, const SkyImageSpec& spec,
                         const BakeContext& ctx);

}  // namespace skybake

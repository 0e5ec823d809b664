// The sky as a cube map for image-based lighting: per listed view
// (altitude, sun zenith) the radiance arriving there from every direction,
// sky plus, below the horizon, the lit ground (docs/runtime.md "Sky
// environment"). Level 0 is the radiance at each texel's centre direction;
// the lower levels are GGX-prefiltered from it (core/ggx_prefilter.hpp),
// in the pipeline's writer.
//
// Frame of a cube: +Y the local zenith, the sun in the x-y plane on the +X
// side, (sin theta_s, cos theta_s, 0); faces in the Direct3D / Vulkan /
// OpenGL order and orientation (core/cube_map.hpp). An engine turns it
// about +Y by the sun's azimuth. Texture: face x face texels, 6 layers per
// view (layer 6 v + f), channels R, G, B, in units of the sun's illuminance
// per steradian like the sky-view LUT.
//
// Each view's L2 spherical harmonics, projected from level 0 with each
// texel's exact solid angle, are in the metadata in sky_irradiance's frame
// and convention (z up, sun in the x-z plane: sky_irradiance.hpp), so that
// an engine's probe and cube agree: view.<v>.sh.<k>, k = 0..8.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "core/bake_context.hpp"
#include "core/ggx_prefilter.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyEnvironmentView {
  double altitude_m = 0.0;
  double sun_zenith_rad = 45.0 * kDeg;
};

struct SkyEnvironmentSpec {
  int face = 128;    // level 0 texels per face side
  int levels = 0;    // level 0 and the prefiltered levels; 0: down to 8 texels per face
  int samples = kGgxDefaultSamples;  // GGX samples per texel of a prefiltered level
  int steps = 40;    // march segments per ray
  bool sky_only = false;
  std::vector<SkyEnvironmentView> views;
};

// The levels a spec asks for: spec.levels, or down to 8 x 8 faces (at least 1).
int sky_environment_levels(const SkyEnvironmentSpec& spec);

// Cube frame <-> sky_irradiance's frame (x toward the sun's azimuth, z up).
glm::dvec3 sky_frame_from_cube(glm::dvec3 d);
// The sun's direction in the cube frame.
glm::dvec3 sky_environment_sun(double sun_zenith_rad);

// The radiance toward cube-frame direction d at one view.
glm::dvec3 sky_environment_radiance(const Atmosphere& atm, const SkyRadianceSource& source,
                                    const SkyEnvironmentSpec& spec, const SkyEnvironmentView& view,
                                    glm::dvec3 d);

// Level 0 of every view, with the metadata (axes, views, SH). Parallel,
// independent of the thread count.
Texture bake_sky_environment(const Atmosphere& atm, const SkyRadianceSource& source,
                             const SkyEnvironmentSpec& spec, const BakeContext& ctx);

// The L2 coefficients of cube `cube` of a level (all nine), in sky_irradiance's frame.
ShRadiance cube_radiance_sh(const Texture& level, int cube);

}  // namespace skybake

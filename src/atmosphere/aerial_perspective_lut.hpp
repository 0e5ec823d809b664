// Aerial-perspective LUT: in-scattering and transmittance between a camera and
// points in front of it, in a volume fit to the camera frustum (Hillaire 2020
// section 5.4; Hillaire 2016).
//
// Shape: width x height x depth froxels (default 32 x 32 x 32, a volume),
// channels R, G, B = luminance in-scattered between the camera and the
// froxel centre (units of Atmosphere::sun_illuminance), A = the mean of the
// R, G, B transmittance over the same path; float32.
//
// Axes: (u, v) = screen position, u left to right, v top to bottom (row 0 is
// the top of the image), texel centres at (i + 0.5) / n; the froxel's ray
// passes through that point of the image plane. Slices are linear in
// distance along the ray (not view-space depth): slice k holds the path of
// length d_k = (k + 0.5) / depth * depth_range_m, so w = d / depth_range_m
// with the same texel-centre convention; the first slice is short (0.5 km by
// default) and between the camera and d_0 lookups fade linearly to
// (0, 0, 0, 1) at distance 0. Linear slices keep the resolution uniform over
// the range that game worlds use (Hillaire's demo squares the distribution to
// favour the near field; the range can be shortened instead).
// Paths that reach the ground before d_k stop there (the froxel sees the
// in-scattering up to the ground; the surface itself is scene geometry), and
// paths past the top of the atmosphere stop at the top.
//
// Camera frame: the camera stands at altitude_m above the planet's ground on
// the local z axis (z = up); yaw is the view azimuth in the horizontal plane
// from +x toward +y, pitch the elevation above it; the sun is given by its
// zenith angle and azimuth in the same frame. The image's right vector is
// horizontal, (sin yaw, -cos yaw, 0), so any pitch, +-90 degrees included,
// has a well-defined frame.
// Ray march: the cumulative march of sky_integrator.hpp,
// steps_per_slice uniform segments between consecutive slice distances.
// Reads: transmittance LUT, multiple-scattering LUT.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/bake_context.hpp"
#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyCamera {
  double altitude_m = 500.0;            // camera altitude above the ground, m
  double yaw_rad = 0.0;                 // view azimuth, from +x toward +y, rad
  double pitch_rad = 0.0;               // view elevation above the horizontal, rad
  double vertical_fov_rad = kPi / 3.0;  // full vertical field of view, rad (0, pi)
  double aspect = 16.0 / 9.0;           // image width / height
};

struct AerialPerspectiveSpec {
  int width = 32;               // froxels across the screen (u)
  int height = 32;              // froxels down the screen (v)
  int depth = 32;               // slices along the view distance (w)
  double depth_range_m = 32e3;  // distance covered by the slices, m
  int steps_per_slice = 2;      // uniform segments between consecutive slice distances
  SkyCamera camera;
  double sun_zenith_rad = kPi / 4;  // sun zenith angle, rad
  double sun_azimuth_rad = 0.0;     // sun azimuth in the camera's local frame, rad
  // Slices, alpha and ground (table_convention.hpp): skybake's above, or
  // hillaire_demo's squared slices over depth_range_m (his 128 km), A = 1 -
  // mean transmittance, and froxels at or below the ground moved onto it.
  TableConvention convention = TableConvention::skybake;
};

// The distance of slice k's froxels in a volume of `spec`.
double aerial_perspective_slice_distance(const AerialPerspectiveSpec& spec, int k);

// Camera basis in the local frame (z up).
struct CameraBasis {
  glm::dvec3 forward, right, up;
};
CameraBasis camera_basis(const SkyCamera& camera);

// Sun direction in the local frame.
glm::dvec3 sun_direction(double sun_zenith_rad, double sun_azimuth_rad);

// Screen position <-> unit view direction (local frame), a perspective
// projection with row 0 at the top. Directions behind the camera (dot with
// forward <= 0) have no screen position: screen_uv_from_view_dir returns NaN
// for them (a sentinel for callers; never written to a texture).
glm::dvec3 view_dir_from_screen_uv(const SkyCamera& camera, glm::dvec2 screen_uv);
glm::dvec2 screen_uv_from_view_dir(const SkyCamera& camera, glm::dvec3 view_dir);

// Froxel coordinates <-> (view direction, distance along it).
struct FroxelView {
  glm::dvec3 view_dir;  // unit, local frame
  double distance_m;    // along view_dir
};
glm::dvec3 aerial_perspective_uvw_from_view(const AerialPerspectiveSpec& spec, FroxelView view);
FroxelView view_from_aerial_perspective_uvw(const AerialPerspectiveSpec& spec, glm::dvec3 uvw);

// Bakes the volume; rows in parallel (tbb::parallel_for), each froxel column
// one cumulative march, independent of the others.
Texture bake_aerial_perspective_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                    const Texture& multiscattering_lut,
                                    const AerialPerspectiveSpec& spec, const BakeContext& ctx);

// RGB in-scattering and A mean transmittance toward screen_uv at distance_m,
// trilinear, fading to (0, 0, 0, 1) at distance 0 before the first slice.
glm::dvec4 lookup_aerial_perspective(const Texture& lut, double depth_range_m, glm::dvec2 screen_uv,
                                     double distance_m);

// The froxel texture read between slices at slice coordinate s >= 0 (slice k
// centred at s = k), bilinear in (u, v), clamped at the last slice: the read
// shared by every slice layout.
glm::dvec4 sample_aerial_slices(const Texture& lut, glm::dvec2 screen_uv, double s);

}  // namespace skybake

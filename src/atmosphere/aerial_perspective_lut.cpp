#include "atmosphere/aerial_perspective_lut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/sky_integrator.hpp"
#include "core/error.hpp"

namespace skybake {

CameraBasis camera_basis(const SkyCamera& camera) {
  const double cp = std::cos(camera.pitch_rad), sp = std::sin(camera.pitch_rad);
  const double cy = std::cos(camera.yaw_rad), sy = std::sin(camera.yaw_rad);
  CameraBasis b;
  b.forward = {cp * cy, cp * sy, sp};
  b.right = {sy, -cy, 0.0};
  b.up = glm::cross(b.right, b.forward);
  return b;
}

glm::dvec3 sun_direction(double sun_zenith_rad, double sun_azimuth_rad) {
  const double s = std::sin(sun_zenith_rad);
  return {s * std::cos(sun_azimuth_rad), s * std::sin(sun_azimuth_rad), std::cos(sun_zenith_rad)};
}

glm::dvec3 view_dir_from_screen_uv(const SkyCamera& camera, glm::dvec2 screen_uv) {
  const CameraBasis b = camera_basis(camera);
  const double tan_half = std::tan(0.5 * camera.vertical_fov_rad);
  const double sx = (2.0 * screen_uv.x - 1.0) * tan_half * camera.aspect;
  const double sy = (1.0 - 2.0 * screen_uv.y) * tan_half;
  return glm::normalize(b.forward + sx * b.right + sy * b.up);
}

glm::dvec2 screen_uv_from_view_dir(const SkyCamera& camera, glm::dvec3 view_dir) {
  const CameraBasis b = camera_basis(camera);
  const double z = glm::dot(view_dir, b.forward);
  if (!(z > 0.0)) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  const double tan_half = std::tan(0.5 * camera.vertical_fov_rad);
  const double sx = glm::dot(view_dir, b.right) / z, sy = glm::dot(view_dir, b.up) / z;
  return {0.5 + 0.5 * sx / (tan_half * camera.aspect), 0.5 - 0.5 * sy / tan_half};
}

glm::dvec3 aerial_perspective_uvw_from_view(const AerialPerspectiveSpec& spec, FroxelView view) {
  const glm::dvec2 uv = screen_uv_from_view_dir(spec.camera, view.view_dir);
  return {uv, view.distance_m / spec.depth_range_m};
}

FroxelView view_from_aerial_perspective_uvw(const AerialPerspectiveSpec& spec, glm::dvec3 uvw) {
  return {view_dir_from_screen_uv(spec.camera, {uvw.x, uvw.y}), uvw.z * spec.depth_range_m};
}

double aerial_perspective_slice_distance(const AerialPerspectiveSpec& spec, int k) {
  if (spec.convention == TableConvention::hillaire_demo)
    return demo_aerial_slice_distance(k, spec.depth, spec.depth_range_m);
  return texel_center(k, spec.depth) * spec.depth_range_m;
}

namespace {

// Hillaire's RenderCameraVolumePS: a froxel whose end point lies within
// kDemoGroundOffsetM of the ground or below it is moved radially to
// kDemoGroundOffsetM + kDemoGroundLiftM above the ground, and its path runs
// straight from the camera to there (stopping at the ground should the
// chord dip below it, as his march's tMax does). False when the froxel
// stays where it is.
bool demo_ground_froxel(const Atmosphere& atm, glm::dvec3 position, glm::dvec3 dir, double d,
                        glm::dvec3& new_dir, double& new_d) {
  const glm::dvec3 end = position + d * dir;
  const double rb = atm.bottom_radius_m;
  if (glm::length(end) > rb + kDemoGroundOffsetM) return false;
  const glm::dvec3 moved = glm::normalize(end) * (rb + kDemoGroundOffsetM + kDemoGroundLiftM);
  new_d = glm::length(moved - position);
  new_dir = (moved - position) / new_d;
  return true;
}

// One froxel column's luminance and transmittance at each slice distance.
std::vector<ScatteringResult> froxel_column(const Atmosphere& atm, const Texture& transmittance_lut,
                                            const Texture& multiscattering_lut,
                                            const AerialPerspectiveSpec& spec,
                                            glm::dvec3 position, glm::dvec3 dir,
                                            glm::dvec3 sun_dir,
                                            const std::vector<double>& distances) {
  std::vector<ScatteringResult> profile = integrate_scattered_luminance_profile(
      atm, transmittance_lut, &multiscattering_lut, position, dir, sun_dir, distances,
      spec.steps_per_slice);
  if (spec.convention != TableConvention::hillaire_demo) return profile;
  for (size_t k = 0; k < distances.size(); ++k) {
    glm::dvec3 moved_dir;
    double moved_d = 0.0;
    if (!demo_ground_froxel(atm, position, dir, distances[k], moved_dir, moved_d)) continue;
    profile[k] = integrate_scattered_luminance(atm, transmittance_lut, &multiscattering_lut,
                                               position, moved_dir, sun_dir, moved_d,
                                               spec.steps_per_slice * int(k + 1));
  }
  return profile;
}

}  // namespace

Texture bake_aerial_perspective_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                    const Texture& multiscattering_lut,
                                    const AerialPerspectiveSpec& spec, const BakeContext& ctx) {
  if (spec.width < 1 || spec.height < 1 || spec.depth < 1 || !(spec.depth_range_m > 0.0))
    throw Error(
        fmt::format("aerial_perspective: expected a positive size and depth range, got "
                    "{}x{}x{} over {} m",
                    spec.width, spec.height, spec.depth, spec.depth_range_m));
  Texture tex(spec.width, spec.height, spec.depth, 1, {"R", "G", "B", "A"});
  std::vector<double> distances(spec.depth);
  for (int k = 0; k < spec.depth; ++k) distances[k] = aerial_perspective_slice_distance(spec, k);
  // His A is the opacity, 1 - mean transmittance; skybake's the transmittance.
  const bool opacity = spec.convention == TableConvention::hillaire_demo;
  const glm::dvec3 position(0.0, 0.0, atm.bottom_radius_m + std::max(spec.camera.altitude_m, 0.0));
  const glm::dvec3 sun_dir = sun_direction(spec.sun_zenith_rad, spec.sun_azimuth_rad);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(0, spec.height, [&](int y) {
    for (int x = 0; x < spec.width; ++x) {
      const glm::dvec3 dir = view_dir_from_screen_uv(
          spec.camera, {texel_center(x, spec.width), texel_center(y, spec.height)});
      const std::vector<ScatteringResult> profile = froxel_column(
          atm, transmittance_lut, multiscattering_lut, spec, position, dir, sun_dir, distances);
      for (int k = 0; k < spec.depth; ++k) {
        float* t = tex.texel(x, y, k);
        for (int c = 0; c < 3; ++c) t[c] = float(profile[k].luminance[c]);
        const glm::dvec3& tr = profile[k].transmittance;
        const double mean = (tr.x + tr.y + tr.z) / 3.0;
        t[3] = float(opacity ? 1.0 - mean : mean);
      }
    }
    progress.tick();
  });
  Metadata& m = tex.metadata;
  set_meta(m, "parameterization", std::string("hillaire2020_aerial_perspective"));
  set_meta(m, "uv", std::string("screen position, texel centres (i + 0.5) / n, row 0 = top"));
  set_meta(m, "w",
           std::string("distance along the view ray / depth_range_m, slice k at "
                       "(k + 0.5) / depth (linear)"));
  set_meta(m, "channels_meaning",
           std::string("RGB in-scattered luminance (units of "
                       "sun_illuminance), A mean RGB transmittance"));
  if (opacity) {
    // Hillaire's RenderCameraVolumePS and its read in RenderRayMarchingPS.
    set_meta(m, "convention", std::string("hillaire_demo"));
    set_meta(m, "w",
             std::string("sqrt(distance along the view ray / depth_range_m), slice k at "
                         "((k + 0.5) / depth)^2 * depth_range_m (squared)"));
    set_meta(m, "channels_meaning",
             std::string("RGB in-scattered luminance (units of sun_illuminance), A opacity "
                         "= 1 - mean RGB transmittance"));
    set_meta(m, "ground",
             std::string("a froxel ending within 10 m of the ground or below it is moved "
                         "radially to 11 m above the ground; its path runs straight there"));
  }
  set_meta(m, "depth_range_m", spec.depth_range_m);
  set_meta(m, "steps_per_slice", spec.steps_per_slice);
  set_meta(m, "camera_altitude_m", spec.camera.altitude_m);
  set_meta(m, "camera_yaw_rad", spec.camera.yaw_rad);
  set_meta(m, "camera_pitch_rad", spec.camera.pitch_rad);
  set_meta(m, "camera_vertical_fov_rad", spec.camera.vertical_fov_rad);
  set_meta(m, "camera_aspect", spec.camera.aspect);
  set_meta(m, "sun_zenith_rad", spec.sun_zenith_rad);
  set_meta(m, "sun_azimuth_rad", spec.sun_azimuth_rad);
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  return tex;
}

glm::dvec4 lookup_aerial_perspective(const Texture& lut, double depth_range_m, glm::dvec2 screen_uv,
                                     double distance_m) {
  const int n = lut.depth;
  const double s = std::max(distance_m, 0.0) / depth_range_m * n - 0.5;  // slice coordinate
  if (s < 0.0) {
    // Before the first slice: fade from the empty path (0, 0, 0, 1) at distance 0.
    // distance / d_0 with d_0 = 0.5 depth_range_m / n the first slice's distance.
    const double f = std::clamp(2.0 * s + 1.0, 0.0, 1.0);
    const glm::dvec4 first = sample_bilinear(lut, screen_uv.x, screen_uv.y, 0, 0, false);
    return glm::mix(glm::dvec4(0.0, 0.0, 0.0, 1.0), first, f);
  }
  return sample_aerial_slices(lut, screen_uv, s);
}

glm::dvec4 sample_aerial_slices(const Texture& lut, glm::dvec2 screen_uv, double s) {
  const int n = lut.depth;
  const int z0 = std::min(int(s), n - 1), z1 = std::min(z0 + 1, n - 1);
  const double f = std::min(s - z0, 1.0);
  const glm::dvec4 a = sample_bilinear(lut, screen_uv.x, screen_uv.y, z0, 0, false);
  const glm::dvec4 b = sample_bilinear(lut, screen_uv.x, screen_uv.y, z1, 0, false);
  return glm::mix(a, b, f);
}

}  // namespace skybake

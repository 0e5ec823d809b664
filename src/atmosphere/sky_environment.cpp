#include "atmosphere/sky_environment.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/cube_map.hpp"

namespace skybake {

int sky_environment_levels(const SkyEnvironmentSpec& spec) {
  if (spec.levels > 0) return spec.levels;
  int levels = 1;
  while ((spec.face >> levels) >= 8) ++levels;
  return levels;
}

glm::dvec3 sky_frame_from_cube(glm::dvec3 d) {
  // A proper rotation taking +Y to +z and keeping +X: the sun's plane to x-z.
  return {d.x, -d.z, d.y};
}

glm::dvec3 sky_environment_sun(double sun_zenith_rad) {
  return {std::sin(sun_zenith_rad), std::cos(sun_zenith_rad), 0.0};
}

glm::dvec3 sky_environment_radiance(const Atmosphere& atm, const SkyRadianceSource& source,
                                    const SkyEnvironmentSpec& spec, const SkyEnvironmentView& view,
                                    glm::dvec3 d) {
  const double height = atm.top_radius_m - atm.bottom_radius_m;
  const double r = atm.bottom_radius_m + std::clamp(view.altitude_m, 0.0, height);
  const glm::dvec3 position(0.0, 0.0, r);
  return sky_source_radiance(atm, source, spec.sky_only, spec.steps, position,
                             sky_frame_from_cube(d),
                             sky_frame_from_cube(sky_environment_sun(view.sun_zenith_rad)));
}

ShRadiance cube_radiance_sh(const Texture& level, int cube) {
  ShRadiance sh;
  sh.fill(glm::dvec3(0.0));
  const int n = level.width;
  for (int f = 0; f < kCubeFaces; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 d = sky_frame_from_cube(cube_texel_direction(f, i, j, n));
        const std::array<double, kShL2Count> y = sh_l2_basis(d);
        const double w = cube_texel_solid_angle(i, j, n);
        const float* t = level.texel(i, j, 0, kCubeFaces * cube + f);
        const glm::dvec3 l(t[0], t[1], t[2]);
        for (int k = 0; k < kShL2Count; ++k) sh[k] += w * y[k] * l;
      }
  return sh;
}

namespace {

void set_sky_environment_metadata(Texture& tex, const Atmosphere& atm,
                                  const SkyRadianceSource& source, const SkyEnvironmentSpec& spec) {
  Metadata& m = tex.metadata;
  set_meta(m, "parameterization", std::string("sky_environment_cube"));
  set_sky_light_source_metadata(m, source);
  set_meta(m, "cube_frame",
           std::string("+Y zenith, sun at (sin theta_s, cos theta_s, 0); faces +X -X +Y -Y +Z -Z"));
  set_meta(m, "views", int(spec.views.size()));
  set_meta(m, "sky_only", spec.sky_only ? 1 : 0);
  set_meta(m, "steps", spec.steps);
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  const int levels = sky_environment_levels(spec);
  set_meta(m, "levels", levels);
  set_meta(m, "prefilter",
           fmt::format("GGX, N = V = R, {} Hammersley samples per texel, filtered importance "
                       "sampling of the box chain",
                       spec.samples));
  set_meta(m, "ggx_samples", spec.samples);
  set_meta(m, "roughness_mapping", std::string("perceptual roughness = level / (levels - 1), alpha = roughness^2"));
  set_meta(m, "sh_frame",
           std::string("z up, sun at azimuth 0 in the x-z plane (sky_irradiance's)"));
  for (size_t v = 0; v < spec.views.size(); ++v) {
    const std::string key = fmt::format("view.{}.", v);
    set_meta(m, key + "altitude_m", spec.views[v].altitude_m);
    set_meta(m, key + "sun_zenith_deg", spec.views[v].sun_zenith_rad / kDeg);
    const ShRadiance sh = cube_radiance_sh(tex, int(v));
    for (int k = 0; k < kShL2Count; ++k) set_meta(m, key + fmt::format("sh.{}", k), sh[k]);
  }
}

}  // namespace

Texture bake_sky_environment(const Atmosphere& atm, const SkyRadianceSource& source,
                             const SkyEnvironmentSpec& spec, const BakeContext& ctx) {
  const int n = spec.face, views = int(spec.views.size());
  Texture tex(n, n, 1, kCubeFaces * views, {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(kCubeFaces * views));
  tbb::parallel_for(0, kCubeFaces * views * n, [&](int row) {
    const int layer = row / n, j = row % n;
    const SkyEnvironmentView& view = spec.views[size_t(layer / kCubeFaces)];
    for (int i = 0; i < n; ++i) {
      // The sky is symmetric about the sun's vertical plane, z = 0 here
      // (docs/runtime.md "Sky environment"): half the texels are marched.
      if (!cube_texel_in_z_half(layer % kCubeFaces, i, j, n)) continue;
      const glm::dvec3 l = sky_environment_radiance(
          atm, source, spec, view, cube_texel_direction(layer % kCubeFaces, i, j, n));
      for (int c = 0; c < 3; ++c) tex.at(i, j, 0, layer, c) = float(l[c]);
    }
    if (j == n - 1) progress.tick();
  });
  fill_z_mirrors(tex);
  set_sky_environment_metadata(tex, atm, source, spec);
  return tex;
}

}  // namespace skybake

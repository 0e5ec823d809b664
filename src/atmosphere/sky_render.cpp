#include "atmosphere/sky_render.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

// Diffuse ground at `point` (any point on or above the ground sphere), lit by
// the sun only: albedo / pi * E * T_sun * max(mu_s, 0).
glm::dvec3 ground_luminance(const Atmosphere& atm, const Texture& transmittance_lut,
                            glm::dvec3 point, glm::dvec3 sun_dir) {
  const double mu_s = clamp_cosine(glm::dot(glm::normalize(point), sun_dir));
  if (mu_s <= 0.0) return glm::dvec3(0.0);
  return atm.ground_albedo / kPi * atm.sun_illuminance * mu_s *
         lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius_m, mu_s);
}

}  // namespace

glm::dvec3 lookup_sun_disk_luminance(const Atmosphere& atm, const Texture& transmittance_lut,
                                     glm::dvec3 position_m, glm::dvec3 view_dir,
                                     glm::dvec3 sun_dir) {
  const double cos_radius = std::cos(atm.sun_angular_radius_rad);
  if (glm::dot(view_dir, sun_dir) < cos_radius) return glm::dvec3(0.0);
  const glm::dvec3 luminance = atm.sun_illuminance / (2.0 * kPi * (1.0 - cos_radius));
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position_m, view_dir);
  if (!span.hits_atmosphere) return luminance;  // in space, the ray misses the planet too
  if (span.exits_on_ground) return glm::dvec3(0.0);
  // Transmittance to the top from where the ray starts inside the atmosphere.
  const glm::dvec3 p = position_m + span.t_enter * view_dir;
  const double r = glm::length(p);
  return luminance * lookup_transmittance_to_top(transmittance_lut, atm, r,
                                                 clamp_cosine(glm::dot(p, view_dir) / r));
}

glm::dvec3 render_sky_luminance(const Atmosphere& atm, const SkyLuts& luts, glm::dvec3 position_m,
                                glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                const SkyRenderOptions& options) {
  const Texture& tlut = *luts.transmittance;
  glm::dvec3 luminance(0.0);
  if (options.sun_disk)
    luminance += lookup_sun_disk_luminance(atm, tlut, position_m, view_dir, sun_dir);
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position_m, view_dir);
  if (!span.hits_atmosphere) return luminance;
  const double r = std::max(glm::length(position_m), atm.bottom_radius_m);
  if (luts.skyview && r <= atm.top_radius_m) {
    const glm::dvec3 up = position_m / glm::length(position_m);
    luminance += lookup_skyview(*luts.skyview, luts.skyview_layer, atm, r,
                                skyview_direction_from_vectors(up, view_dir, sun_dir));
    if (options.ground && span.exits_on_ground) {
      const double mu = clamp_cosine(glm::dot(up, view_dir));
      const glm::dvec3 t_view = lookup_transmittance(tlut, atm, r, mu, span.t_exit, true);
      luminance +=
          t_view * ground_luminance(atm, tlut, position_m + span.t_exit * view_dir, sun_dir);
    }
    return luminance;
  }
  const IntegrationOptions march{StepDistribution::uniform, options.ground};
  luminance += integrate_scattered_luminance(atm, tlut, luts.multiscattering, position_m, view_dir,
                                             sun_dir, INFINITY, options.march_steps, march)
                   .luminance;
  return luminance;
}

Texture render_sky_image(const Atmosphere& atm, const SkyLuts& luts, const SkyImageSpec& spec,
                         const BakeContext& ctx) {
  Texture img(spec.width, spec.height, 1, 1, {"R", "G", "B"});
  const glm::dvec3 position(0.0, 0.0, atm.bottom_radius_m + std::max(spec.camera.altitude_m, 0.0));
  const glm::dvec3 sun_dir = sun_direction(spec.sun_zenith_rad, spec.sun_azimuth_rad);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(0, spec.height, [&](int y) {
    for (int x = 0; x < spec.width; ++x) {
      const glm::dvec2 uv(texel_center(x, spec.width), texel_center(y, spec.height));
      const glm::dvec3 dir = view_dir_from_screen_uv(spec.camera, uv);
      glm::dvec3 l;
      const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, dir);
      if (luts.aerial_perspective && spec.options.ground && span.hits_atmosphere &&
          span.exits_on_ground && span.t_enter == 0.0 &&
          span.t_exit <= luts.aerial_perspective_range_m) {
        // An engine's opaque ground: its lit colour through the froxel volume.
        const glm::dvec4 ap = lookup_aerial_perspective(
            *luts.aerial_perspective, luts.aerial_perspective_range_m, uv, span.t_exit);
        l = ground_luminance(atm, *luts.transmittance, position + span.t_exit * dir, sun_dir) *
                ap.w +
            glm::dvec3(ap);
      } else {
        l = render_sky_luminance(atm, luts, position, dir, sun_dir, spec.options);
      }
      float* t = img.texel(x, y);
      for (int c = 0; c < 3; ++c) t[c] = float(l[c]);
    }
    progress.tick();
  });
  set_meta(img.metadata, "units", std::string("luminance, units of sun_illuminance"));
  return img;
}

}  // namespace skybake

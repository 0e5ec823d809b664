// requires: atmosphere_common.glsl, transmittance.glsl
// skybake runtime: the sky-view LUT and the aerial-perspective volume with
// Hillaire 2020's run-time formulas (sec. 5.3-5.4): the distant sky from the
// sky-view LUT plus the sun disk through the transmittance LUT, and a
// surface seen through the froxel volume as L = L_surface T + L_in.
// C++: src/atmosphere/skyview_lut.hpp, aerial_perspective_lut.hpp,
// sky_render.hpp; docs/reference.md "Sky-view", "Aerial perspective", "Sun
// disk and previews".
//
// The textures (docs/runtime.md "Sky-view", "Aerial perspective"):
// - skyview.dds: a 2D array, one layer per (viewer altitude, sun zenith)
//   listed in the metadata; RGB linear float; bilinear, REPEAT in u (the
//   azimuth wraps), clamp to edge in v; no mips. Bind as sampler2DArray
//   (one layer too).
// - aerial_perspective.dds: a volume, RGB in-scattering and A mean
//   transmittance; trilinear, clamp to edge; no mips.

// ---- Sky-view ---------------------------------------------------------------

// A view direction in a layer's frame: z the viewer's zenith, the sun in the
// x-z plane at azimuth 0.
struct SkyviewDirection {
  float mu;       // cosine of the view zenith angle
  float azimuth;  // from the sun's vertical plane, rad, [0, 2 pi)
};

float wrap_azimuth(float phi) {
  phi = mod(phi, 2.0 * kPi);
  return phi < 2.0 * kPi ? phi : 0.0;
}

// beta, the angular radius of the ground seen from r, cos(beta) =
// sqrt(r^2 - Rb^2) / r (atan form: accurate at the ground), floored so the
// ground half stays invertible far from the planet. The horizon's zenith
// angle is pi - beta.
float skyview_beta(AtmosphereParameters atm, float r) {
  float rb = atm.bottom_radius;
  r = max(r, rb);
  return max(accurate_atan2(rb, safe_sqrt((r - rb) * (r + rb))), 1e-9);
}

// Hillaire 2020 sec. 5.3's quadratic latitude mapping, generalised to the
// viewer's altitude (his demo) and flipped so row 0 is the zenith:
//   l = Z - theta, Z = pi - beta,
//   x = 0.5 - 0.5 sqrt(l / Z) (sky), 0.5 + 0.5 sqrt(-l / beta) (ground),
//   u = azimuth / (2 pi) (texel i centred at 2 pi (i + 0.5) / W), v = coord(x, H).
vec2 skyview_uv_from_view(AtmosphereParameters atm, float r, SkyviewDirection view, int width,
                          int height) {
  float beta = skyview_beta(atm, r);
  float zenith_horizon = kPi - beta;
  float theta = accurate_acos(view.mu);
  float l = zenith_horizon - theta;
  float x = l >= 0.0 ? 0.5 - 0.5 * sqrt(l / zenith_horizon)
                     : 0.5 + 0.5 * sqrt(min(-l / beta, 1.0));
  return vec2(wrap_azimuth(view.azimuth) / (2.0 * kPi),
              texel_coord_from_unit(clamp(x, 0.0, 1.0), height));
}

// The exact inverse at viewer radius r: theta = Z (1 - (1 - 2x)^2) above the
// horizon, Z + beta (2x - 1)^2 below it; azimuth 2 pi u.
SkyviewDirection view_from_skyview_uv(AtmosphereParameters atm, float r, vec2 uv, int width,
                                      int height) {
  float beta = skyview_beta(atm, r);
  float zenith_horizon = kPi - beta;
  float x = clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  float theta = x < 0.5 ? zenith_horizon * (1.0 - (1.0 - 2.0 * x) * (1.0 - 2.0 * x))
                        : zenith_horizon + beta * (2.0 * x - 1.0) * (2.0 * x - 1.0);
  return SkyviewDirection(cos(theta), wrap_azimuth(2.0 * kPi * uv.x));
}

// The unit view vector of a layer-frame direction (z up, the sun at azimuth 0).
vec3 skyview_vector_from_direction(SkyviewDirection view) {
  float sin_theta = safe_sqrt(1.0 - view.mu * view.mu);
  return vec3(sin_theta * cos(view.azimuth), sin_theta * sin(view.azimuth), clamp_cosine(view.mu));
}

// The layer-frame direction of a world view direction: mu against `up` (the
// viewer's zenith, normalised position), azimuth from the sun's vertical plane.
SkyviewDirection skyview_direction_from_vectors(vec3 up, vec3 view_dir, vec3 sun_dir) {
  float mu = clamp_cosine(dot(view_dir, up));
  vec3 view_h = view_dir - mu * up;
  vec3 sun_h = sun_dir - dot(sun_dir, up) * up;
  if (dot(sun_h, sun_h) < 1e-12)  // the sun at the zenith or nadir: any reference azimuth
    sun_h = cross(up, abs(up.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
  vec3 forward = normalize(sun_h);
  vec3 side = cross(up, forward);
  if (dot(view_h, view_h) < 1e-14) return SkyviewDirection(mu, 0.0);
  return SkyviewDirection(mu, wrap_azimuth(accurate_atan2(dot(view_h, side), dot(view_h, forward))));
}

// In-scattered luminance of layer `layer` (baked for the viewer radius r)
// toward `view`, bilinear; the sampler repeats in u.
vec3 lookup_skyview(sampler2DArray lut, int layer, AtmosphereParameters atm, float r,
                    SkyviewDirection view) {
  ivec3 size = textureSize(lut, 0);
  vec2 uv = skyview_uv_from_view(atm, r, view, size.x, size.y);
  return textureLod(lut, vec3(uv, float(layer)), 0.0).rgb;
}

// ---- The sun disk ------------------------------------------------------------

// Where a ray from `position` (planet-centred, m) along unit `dir` is inside
// the atmosphere: entering at t_enter (0 inside, > 0 from space), leaving at
// t_exit on the top or the ground. (sky_integrator.hpp clip_ray_to_atmosphere)
struct AtmosphereSpan {
  bool hits_atmosphere;
  bool exits_on_ground;
  float t_enter, t_exit;  // m along dir
};

AtmosphereSpan clip_ray_to_atmosphere(AtmosphereParameters atm, vec3 position, vec3 dir) {
  float rb = atm.bottom_radius, rt = atm.top_radius;
  float len = length(position);
  float r = max(len, rb);
  float mu = len > 0.0 ? clamp_cosine(dot(position, dir) / len) : 1.0;
  AtmosphereSpan span = AtmosphereSpan(false, false, 0.0, 0.0);
  float r_in = r, mu_in = mu;
  if (r > rt) {
    // Above the top: enter where the ray first meets the top sphere, if it does.
    float disc = (r * mu) * (r * mu) - (r - rt) * (r + rt);
    if (mu >= 0.0 || disc < 0.0) return span;
    span.t_enter = max(0.0, -r * mu - sqrt(disc));
    r_in = rt;
    mu_in = clamp_cosine((r * mu + span.t_enter) / rt);
  }
  span.hits_atmosphere = true;
  span.exits_on_ground = ray_intersects_ground(rb, r_in, mu_in);
  span.t_exit = span.t_enter + (span.exits_on_ground ? distance_to_bottom_boundary(rb, r_in, mu_in)
                                                     : distance_to_top_boundary(rt, r_in, mu_in));
  return span;
}

// The sun as a uniform disk of angular radius alpha: luminance
// E / (2 pi (1 - cos alpha)) (Hillaire 2016 eq. 14) times the transmittance
// to the top along view_dir; 0 outside the disk or when the ground hides it.
vec3 lookup_sun_disk_luminance(AtmosphereParameters atm, sampler2D transmittance_lut,
                               vec3 position, vec3 view_dir, vec3 sun_dir) {
  float cos_radius = cos(atm.sun_angular_radius);
  if (dot(view_dir, sun_dir) < cos_radius) return vec3(0.0);
  vec3 luminance = atm.sun_illuminance / (2.0 * kPi * one_minus_cos(atm.sun_angular_radius));
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, view_dir);
  if (!span.hits_atmosphere) return luminance;
  if (span.exits_on_ground) return vec3(0.0);
  vec3 p = position + span.t_enter * view_dir;
  float r = length(p);
  return luminance *
         lookup_transmittance_to_top(transmittance_lut, atm, r, clamp_cosine(dot(p, view_dir) / r));
}

// Hillaire 2020 sec. 5.3 at run time: the sky toward view_dir from a viewer
// inside the atmosphere, sky-view layer `layer` (baked for this viewer's
// altitude and sun) plus the sun disk. The ground itself is scene geometry.
vec3 sky_luminance(sampler2DArray skyview_lut, int layer, sampler2D transmittance_lut,
                   AtmosphereParameters atm, vec3 position, vec3 view_dir, vec3 sun_dir) {
  float r = max(length(position), atm.bottom_radius);
  vec3 up = position / length(position);
  return lookup_skyview(skyview_lut, layer, atm, r,
                        skyview_direction_from_vectors(up, view_dir, sun_dir)) +
         lookup_sun_disk_luminance(atm, transmittance_lut, position, view_dir, sun_dir);
}

// ---- Aerial perspective ---------------------------------------------------------

// RGB in-scattering and A mean transmittance between the camera and the
// point at distance_m along the ray through screen_uv (row 0 at the top),
// trilinear; slice k holds distance (k + 0.5) / depth * depth_range_m, and
// before the first slice the value fades to (0, 0, 0, 1) at distance 0.
vec4 lookup_aerial_perspective(sampler3D lut, float depth_range_m, vec2 screen_uv,
                               float distance_m) {
  float n = float(textureSize(lut, 0).z);
  float s = max(distance_m, 0.0) / depth_range_m * n - 0.5;  // slice coordinate
  if (s < 0.0) {
    float f = clamp(2.0 * s + 1.0, 0.0, 1.0);
    vec4 first = textureLod(lut, vec3(screen_uv, 0.5 / n), 0.0);
    return mix(vec4(0.0, 0.0, 0.0, 1.0), first, f);
  }
  // Between slices z0 and z0 + 1 the hardware's lerp in w is the slices' lerp.
  return textureLod(lut, vec3(screen_uv, (min(s, n - 1.0) + 0.5) / n), 0.0);
}

// Hillaire 2020 sec. 5.4: a surface of luminance L seen through the volume,
// L T + L_in (T the mean transmittance of the froxel, L_in its in-scattering).
vec3 apply_aerial_perspective(vec3 surface_luminance, vec4 aerial) {
  return surface_luminance * aerial.a + aerial.rgb;
}

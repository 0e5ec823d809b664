// requires: atmosphere_common.glsl, transmittance.glsl, multiscattering.glsl, sky_view.glsl
// skybake runtime: reads of the tables baked with "convention": "hillaire_demo"
// (docs/runtime.md "Using skybake's tables in a renderer derived from
// Hillaire's demo"). Each table keeps its own mapping to a unit axis x in
// [0, 1] (transmittance.glsl, multiscattering.glsl, sky_view.glsl); the
// convention changes where x sits in the texture. C++:
// src/atmosphere/table_convention.hpp, hillaire_demo_lookups.hpp.
//
// All four textures: bilinear (trilinear), clamp to edge on every axis, no mips.

// Where a reader through (x n + 0.5) / (n + 1) (Hillaire's fromUnitToSubUvs)
// finds x: the multiscattering and sky-view axes.
float demo_sub_uv(float x, int n) { return (x * float(n) + 0.5) / float(n + 1); }

// Transmittance: u = x_mu, v = x_r read directly (texel i holds x = (i + 0.5) / n).
vec2 demo_transmittance_uv_from_r_mu(AtmosphereParameters atm, float r, float mu, int width,
                                     int height) {
  vec2 uv = transmittance_uv_from_r_mu(atm, r, mu, width, height);
  return vec2(clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0),
              clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0));
}

vec3 lookup_demo_transmittance_to_top(sampler2D lut, AtmosphereParameters atm, float r, float mu) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, demo_transmittance_uv_from_r_mu(atm, r, mu, size.x, size.y), 0.0).rgb;
}

// Multiscattering (linear axes): x_mu_s = 0.5 + 0.5 mu_s, x_h = (r - Rb) / (Rt - Rb).
vec2 demo_multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                         int height) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float x_mu_s = clamp(0.5 + 0.5 * mu_s, 0.0, 1.0);
  float x_h = (r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius);
  return vec2(demo_sub_uv(x_mu_s, width), demo_sub_uv(x_h, height));
}

vec3 lookup_demo_multiscattering(sampler2D lut, AtmosphereParameters atm, float r, float mu_s) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, demo_multiscattering_uv_from_r_mu_s(atm, r, mu_s, size.x, size.y), 0.0)
      .rgb;
}

// Sky-view: the azimuth over the half circle, x = sqrt(0.5 - 0.5 cos phi)
// (the sun at 0), the latitude skybake's; both through demo_sub_uv.
vec2 demo_skyview_uv_from_view(AtmosphereParameters atm, float r, SkyviewDirection view,
                               int width, int height) {
  float v = skyview_uv_from_view(atm, r, view, width, height).y;
  float x_v = clamp(unit_from_texel_coord(v, height), 0.0, 1.0);
  float x_u = sqrt(clamp(0.5 - 0.5 * cos(view.azimuth), 0.0, 1.0));
  return vec2(demo_sub_uv(x_u, width), demo_sub_uv(x_v, height));
}

vec3 lookup_demo_skyview(sampler2DArray lut, int layer, AtmosphereParameters atm, float r,
                         SkyviewDirection view) {
  ivec3 size = textureSize(lut, 0);
  vec2 uv = demo_skyview_uv_from_view(atm, r, view, size.x, size.y);
  return textureLod(lut, vec3(uv, float(layer)), 0.0).rgb;
}

// Aerial perspective: slice k of n at ((k + 0.5) / n)^2 depth_range_m, read
// at w = sqrt(d / depth_range_m); A is the opacity 1 - mean transmittance.
// Before the first slice a linear fade to (0, 0, 0, 0) at distance 0.
vec4 lookup_demo_aerial_perspective(sampler3D lut, float depth_range_m, vec2 screen_uv,
                                    float distance_m) {
  float n = float(textureSize(lut, 0).z);
  float d = max(distance_m, 0.0);
  float w = sqrt(d / depth_range_m);
  float d0 = (0.5 / n) * (0.5 / n) * depth_range_m;
  if (d < d0) return textureLod(lut, vec3(screen_uv, 0.5 / n), 0.0) * (d / d0);
  return textureLod(lut, vec3(screen_uv, w), 0.0);
}

// A surface of luminance L seen through the volume: L (1 - A) + RGB.
vec3 apply_demo_aerial_perspective(vec3 surface_luminance, vec4 aerial) {
  return surface_luminance * (1.0 - aerial.a) + aerial.rgb;
}

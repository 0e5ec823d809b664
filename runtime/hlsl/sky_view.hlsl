// requires: atmosphere_common.hlsl, transmittance.hlsl
// skybake runtime: the sky-view LUT and the aerial-perspective volume with
// Hillaire 2020's run-time formulas (sec. 5.3-5.4), HLSL twin of
// runtime/glsl/sky_view.glsl (C++ src/atmosphere/skyview_lut.hpp,
// aerial_perspective_lut.hpp, sky_render.hpp; docs/reference.md "Sky-view",
// "Aerial perspective"). Samplers (docs/runtime.md): sky-view a Texture2DArray,
// bilinear, WRAP in u and CLAMP in v; aerial perspective a Texture3D,
// trilinear, CLAMP.

struct SkyviewDirection {
  float mu;       // cosine of the view zenith angle
  float azimuth;  // from the sun's vertical plane, rad, [0, 2 pi)
};

SkyviewDirection make_skyview_direction(float mu, float azimuth) {
  SkyviewDirection d;
  d.mu = mu;
  d.azimuth = azimuth;
  return d;
}

// Floor-based: HLSL's fmod keeps the sign of its argument.
float wrap_azimuth(float phi) {
  phi = phi - 2.0 * kPi * floor(phi / (2.0 * kPi));
  return phi < 2.0 * kPi ? phi : 0.0;
}

float skyview_beta(AtmosphereParameters atm, float r) {
  float rb = atm.bottom_radius;
  r = max(r, rb);
  return max(accurate_atan2(rb, safe_sqrt((r - rb) * (r + rb))), 1e-9);
}

// Hillaire 2020 sec. 5.3's latitude mapping at the viewer's altitude, row 0 the zenith.
float2 skyview_uv_from_view(AtmosphereParameters atm, float r, SkyviewDirection view, int width,
                            int height) {
  float beta = skyview_beta(atm, r);
  float zenith_horizon = kPi - beta;
  float theta = accurate_acos(view.mu);
  float l = zenith_horizon - theta;
  float x = l >= 0.0 ? 0.5 - 0.5 * sqrt(l / zenith_horizon)
                     : 0.5 + 0.5 * sqrt(min(-l / beta, 1.0));
  return float2(wrap_azimuth(view.azimuth) / (2.0 * kPi),
                texel_coord_from_unit(clamp(x, 0.0, 1.0), height));
}

// The exact inverse at viewer radius r: theta = Z (1 - (1 - 2x)^2) above the
// horizon, Z + beta (2x - 1)^2 below it; azimuth 2 pi u.
SkyviewDirection view_from_skyview_uv(AtmosphereParameters atm, float r, float2 uv, int width,
                                      int height) {
  float beta = skyview_beta(atm, r);
  float zenith_horizon = kPi - beta;
  float x = clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  float theta = x < 0.5 ? zenith_horizon * (1.0 - (1.0 - 2.0 * x) * (1.0 - 2.0 * x))
                        : zenith_horizon + beta * (2.0 * x - 1.0) * (2.0 * x - 1.0);
  return make_skyview_direction(cos(theta), wrap_azimuth(2.0 * kPi * uv.x));
}

// The unit view vector of a layer-frame direction (z up, the sun at azimuth 0).
float3 skyview_vector_from_direction(SkyviewDirection view) {
  float sin_theta = safe_sqrt(1.0 - view.mu * view.mu);
  return float3(sin_theta * cos(view.azimuth), sin_theta * sin(view.azimuth), clamp_cosine(view.mu));
}

SkyviewDirection skyview_direction_from_vectors(float3 up, float3 view_dir, float3 sun_dir) {
  float mu = clamp_cosine(dot(view_dir, up));
  float3 view_h = view_dir - mu * up;
  float3 sun_h = sun_dir - dot(sun_dir, up) * up;
  if (dot(sun_h, sun_h) < 1e-12)
    sun_h = cross(up, abs(up.x) < 0.9 ? float3(1.0, 0.0, 0.0) : float3(0.0, 1.0, 0.0));
  float3 forward = normalize(sun_h);
  float3 side = cross(up, forward);
  if (dot(view_h, view_h) < 1e-14) return make_skyview_direction(mu, 0.0);
  return make_skyview_direction(mu, wrap_azimuth(accurate_atan2(dot(view_h, side), dot(view_h, forward))));
}

float3 lookup_skyview(Texture2DArray<float4> lut, SamplerState lut_sampler, int layer,
                      AtmosphereParameters atm, float r, SkyviewDirection view) {
  uint width, height, layers;
  lut.GetDimensions(width, height, layers);
  float2 uv = skyview_uv_from_view(atm, r, view, int(width), int(height));
  return lut.SampleLevel(lut_sampler, float3(uv, float(layer)), 0.0).rgb;
}

// ---- The sun disk

struct AtmosphereSpan {
  bool hits_atmosphere;
  bool exits_on_ground;
  float t_enter, t_exit;  // m along dir
};

AtmosphereSpan clip_ray_to_atmosphere(AtmosphereParameters atm, float3 position, float3 dir) {
  float rb = atm.bottom_radius, rt = atm.top_radius;
  float len = length(position);
  float r = max(len, rb);
  float mu = len > 0.0 ? clamp_cosine(dot(position, dir) / len) : 1.0;
  AtmosphereSpan span;
  span.hits_atmosphere = false;
  span.exits_on_ground = false;
  span.t_enter = 0.0;
  span.t_exit = 0.0;
  float r_in = r, mu_in = mu;
  if (r > rt) {
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

// E / (2 pi (1 - cos alpha)) (Hillaire 2016 eq. 14) through the transmittance to the top.
float3 lookup_sun_disk_luminance(AtmosphereParameters atm, Texture2D<float4> transmittance_lut,
                                 SamplerState transmittance_sampler, float3 position,
                                 float3 view_dir, float3 sun_dir) {
  float cos_radius = cos(atm.sun_angular_radius);
  if (dot(view_dir, sun_dir) < cos_radius) return float3(0.0, 0.0, 0.0);
  float3 luminance = atm.sun_illuminance / (2.0 * kPi * one_minus_cos(atm.sun_angular_radius));
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, view_dir);
  if (!span.hits_atmosphere) return luminance;
  if (span.exits_on_ground) return float3(0.0, 0.0, 0.0);
  float3 p = position + span.t_enter * view_dir;
  float r = length(p);
  return luminance * lookup_transmittance_to_top(transmittance_lut, transmittance_sampler, atm, r,
                                                 clamp_cosine(dot(p, view_dir) / r));
}

// Hillaire 2020 sec. 5.3: the sky-view layer plus the sun disk.
float3 sky_luminance(Texture2DArray<float4> skyview_lut, SamplerState skyview_sampler, int layer,
                     Texture2D<float4> transmittance_lut, SamplerState transmittance_sampler,
                     AtmosphereParameters atm, float3 position, float3 view_dir, float3 sun_dir) {
  float r = max(length(position), atm.bottom_radius);
  float3 up = position / length(position);
  return lookup_skyview(skyview_lut, skyview_sampler, layer, atm, r,
                        skyview_direction_from_vectors(up, view_dir, sun_dir)) +
         lookup_sun_disk_luminance(atm, transmittance_lut, transmittance_sampler, position,
                                   view_dir, sun_dir);
}

// ---- Aerial perspective

float4 lookup_aerial_perspective(Texture3D<float4> lut, SamplerState lut_sampler,
                                 float depth_range_m, float2 screen_uv, float distance_m) {
  uint width, height, depth;
  lut.GetDimensions(width, height, depth);
  float n = float(depth);
  float s = max(distance_m, 0.0) / depth_range_m * n - 0.5;
  if (s < 0.0) {
    float f = clamp(2.0 * s + 1.0, 0.0, 1.0);
    float4 first = lut.SampleLevel(lut_sampler, float3(screen_uv, 0.5 / n), 0.0);
    return lerp(float4(0.0, 0.0, 0.0, 1.0), first, f);
  }
  return lut.SampleLevel(lut_sampler, float3(screen_uv, (min(s, n - 1.0) + 0.5) / n), 0.0);
}

// Hillaire 2020 sec. 5.4: L T + L_in.
float3 apply_aerial_perspective(float3 surface_luminance, float4 aerial) {
  return surface_luminance * aerial.a + aerial.rgb;
}

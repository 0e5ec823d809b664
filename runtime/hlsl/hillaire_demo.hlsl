// requires: atmosphere_common.hlsl, transmittance.hlsl, multiscattering.hlsl, sky_view.hlsl
// skybake runtime: reads of the tables baked with "convention": "hillaire_demo",
// HLSL twin of runtime/glsl/hillaire_demo.glsl (docs/runtime.md "Using
// skybake's tables in a renderer derived from Hillaire's demo"; C++
// src/atmosphere/table_convention.hpp, hillaire_demo_lookups.hpp). Samplers:
// bilinear (trilinear), CLAMP on every axis.

float demo_sub_uv(float x, int n) { return (x * float(n) + 0.5) / float(n + 1); }

float2 demo_transmittance_uv_from_r_mu(AtmosphereParameters atm, float r, float mu, int width,
                                       int height) {
  float2 uv = transmittance_uv_from_r_mu(atm, r, mu, width, height);
  return float2(clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0),
                clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0));
}

float3 lookup_demo_transmittance_to_top(Texture2D<float4> lut, SamplerState lut_sampler,
                                        AtmosphereParameters atm, float r, float mu) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         demo_transmittance_uv_from_r_mu(atm, r, mu, int(width), int(height)), 0.0)
      .rgb;
}

float2 demo_multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s,
                                           int width, int height) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float x_mu_s = clamp(0.5 + 0.5 * mu_s, 0.0, 1.0);
  float x_h = (r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius);
  return float2(demo_sub_uv(x_mu_s, width), demo_sub_uv(x_h, height));
}

float3 lookup_demo_multiscattering(Texture2D<float4> lut, SamplerState lut_sampler,
                                   AtmosphereParameters atm, float r, float mu_s) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         demo_multiscattering_uv_from_r_mu_s(atm, r, mu_s, int(width),
                                                             int(height)), 0.0)
      .rgb;
}

float2 demo_skyview_uv_from_view(AtmosphereParameters atm, float r, SkyviewDirection view,
                                 int width, int height) {
  float v = skyview_uv_from_view(atm, r, view, width, height).y;
  float x_v = clamp(unit_from_texel_coord(v, height), 0.0, 1.0);
  float x_u = sqrt(clamp(0.5 - 0.5 * cos(view.azimuth), 0.0, 1.0));
  return float2(demo_sub_uv(x_u, width), demo_sub_uv(x_v, height));
}

float3 lookup_demo_skyview(Texture2DArray<float4> lut, SamplerState lut_sampler, int layer,
                           AtmosphereParameters atm, float r, SkyviewDirection view) {
  uint width, height, layers;
  lut.GetDimensions(width, height, layers);
  float2 uv = demo_skyview_uv_from_view(atm, r, view, int(width), int(height));
  return lut.SampleLevel(lut_sampler, float3(uv, float(layer)), 0.0).rgb;
}

float4 lookup_demo_aerial_perspective(Texture3D<float4> lut, SamplerState lut_sampler,
                                      float depth_range_m, float2 screen_uv, float distance_m) {
  uint width, height, depth;
  lut.GetDimensions(width, height, depth);
  float n = float(depth);
  float d = max(distance_m, 0.0);
  float d0 = (0.5 / n) * (0.5 / n) * depth_range_m;
  if (d < d0) return lut.SampleLevel(lut_sampler, float3(screen_uv, 0.5 / n), 0.0) * (d / d0);
  return lut.SampleLevel(lut_sampler, float3(screen_uv, sqrt(d / depth_range_m)), 0.0);
}

float3 apply_demo_aerial_perspective(float3 surface_luminance, float4 aerial) {
  return surface_luminance * (1.0 - aerial.a) + aerial.rgb;
}

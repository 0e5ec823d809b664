// requires: atmosphere_common.hlsl
// skybake runtime: the multiple-scattering LUT Psi_ms, HLSL twin of
// runtime/glsl/multiscattering.glsl (Hillaire 2020 sec. 5.5; C++
// src/atmosphere/multiscattering_lut.hpp). RGB linear float, bilinear,
// clamp to edge, no mips (docs/runtime.md "Multiple scattering").

float2 multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                      int height) {
  float x_mu_s = 0.5 + 0.5 * clamp_cosine(mu_s);
  float x_h = clamp((r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius), 0.0, 1.0);
  return float2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

float3 lookup_multiscattering(Texture2D<float4> lut, SamplerState lut_sampler,
                              AtmosphereParameters atm, float r, float mu_s) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         multiscattering_uv_from_r_mu_s(atm, r, mu_s, int(width), int(height)), 0.0)
      .rgb;
}

// The terminator sun mapping (metadata mu_s_mapping = "terminator"; twin of
// the GLSL function): w = mu_s_mapping_width, offset = mu_s_mapping_offset.
float2 multiscattering_uv_from_r_mu_s_terminator(AtmosphereParameters atm, float r, float mu_s,
                                                 float w, float offset, int width, int height) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float ratio = atm.bottom_radius / r;
  float c = -safe_sqrt(1.0 - ratio * ratio) - offset;
  float a_lo = accurate_atan((-1.0 - c) / w);
  float a_hi = accurate_atan((1.0 - c) / w);
  float x_mu_s = clamp((accurate_atan((clamp_cosine(mu_s) - c) / w) - a_lo) / (a_hi - a_lo), 0.0,
                       1.0);
  float x_h = (r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius);
  return float2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

float3 lookup_multiscattering_terminator(Texture2D<float4> lut, SamplerState lut_sampler,
                                         AtmosphereParameters atm, float r, float mu_s, float w,
                                         float offset) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         multiscattering_uv_from_r_mu_s_terminator(atm, r, mu_s, w, offset,
                                                                   int(width), int(height)),
                         0.0)
      .rgb;
}

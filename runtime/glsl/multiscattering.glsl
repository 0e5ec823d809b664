// requires: atmosphere_common.glsl
// skybake runtime: the multiple-scattering LUT Psi_ms (Hillaire 2020 sec.
// 5.5, eq. 10), the transfer of every order >= 2 toward a point, isotropic
// after the first bounce, in 1/sr (multiply by the sun's illuminance and
// sigma_s: eq. 11). C++: src/atmosphere/multiscattering_lut.hpp;
// docs/reference.md "Multiple scattering (Hillaire)".
//
// The texture: multiscattering.dds / .exr, RGB linear float, bilinear, clamp
// to edge, no mips (docs/runtime.md "Multiple scattering").

// Hillaire 2020 sec. 5.5.2 on texel centres:
//   u = coord(0.5 + 0.5 mu_s, W), v = coord((r - Rb) / (Rt - Rb), H).
vec2 multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                    int height) {
  float x_mu_s = 0.5 + 0.5 * clamp_cosine(mu_s);
  float x_h = clamp((r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius), 0.0, 1.0);
  return vec2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

// Psi_ms at radius r (clamped to the shell) for a sun of zenith cosine mu_s, bilinear.
vec3 lookup_multiscattering(sampler2D lut, AtmosphereParameters atm, float r, float mu_s) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, multiscattering_uv_from_r_mu_s(atm, r, mu_s, size.x, size.y), 0.0).rgb;
}

// The terminator sun mapping, for a table whose metadata says
// mu_s_mapping = "terminator" (option sun_mapping; docs/reference.md
// "Terminator mapping"): w = mu_s_mapping_width, offset = mu_s_mapping_offset.
//   c = -sqrt(1 - (Rb / r)^2) - offset,  a(m) = atan((m - c) / w),
//   x_mu_s = (a(mu_s) - a(-1)) / (a(1) - a(-1)).
vec2 multiscattering_uv_from_r_mu_s_terminator(AtmosphereParameters atm, float r, float mu_s,
                                               float w, float offset, int width, int height) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float ratio = atm.bottom_radius / r;
  float c = -safe_sqrt(1.0 - ratio * ratio) - offset;
  float a_lo = accurate_atan((-1.0 - c) / w);
  float a_hi = accurate_atan((1.0 - c) / w);
  float x_mu_s = clamp((accurate_atan((clamp_cosine(mu_s) - c) / w) - a_lo) / (a_hi - a_lo), 0.0,
                       1.0);
  float x_h = (r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius);
  return vec2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

vec3 lookup_multiscattering_terminator(sampler2D lut, AtmosphereParameters atm, float r,
                                       float mu_s, float w, float offset) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut,
                    multiscattering_uv_from_r_mu_s_terminator(atm, r, mu_s, w, offset, size.x,
                                                              size.y),
                    0.0).rgb;
}

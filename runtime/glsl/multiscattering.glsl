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

// requires: atmosphere_common.glsl
// skybake runtime: the multiple-scattering LUT Psi_ms (Hillaire 2020 sec.
// 5.5, eq. 10), the transfer of every order >= 2 toward a point, isotropic
// after the first bounce, in 1/sr (multiply by the sun's illuminance and
// sigma_s: eq. 11). C++: src/atmosphere/multiscattering_lut.hpp;
// docs/reference.md "Multiple scattering (Hillaire)".
//
// The texture: multiscattering.dds / .exr, RGB linear float, bilinear, clamp
// to edge, no mips (docs/runtime.md "Multiple scattering"). Its sun axis is
// linear in mu_s, or the terminator mapping the metadata names
// (mu_s_mapping, mu_s_mapping_width, mu_s_mapping_offset); its altitude axis
// linear or quadratic (altitude_mapping).

const int MULTISCATTERING_SUN_LINEAR = 0;
const int MULTISCATTERING_SUN_TERMINATOR = 1;
const int MULTISCATTERING_ALTITUDE_LINEAR = 0;
const int MULTISCATTERING_ALTITUDE_QUADRATIC = 1;

struct MultiscatteringMapping {
  int sun;       // MULTISCATTERING_SUN_LINEAR or MULTISCATTERING_SUN_TERMINATOR
  float width;   // terminator: w, the crowded span in mu_s
  float offset;  // terminator: how far below the horizon's cosine the centre sits
  int altitude;  // MULTISCATTERING_ALTITUDE_LINEAR or MULTISCATTERING_ALTITUDE_QUADRATIC
};

// x_mu_s in [0, 1] (before texel centring): 0.5 + 0.5 mu_s, or around the
// terminator (docs/reference.md "Multiple scattering"):
//   c(r) = mu_h(r) - offset, a(mu_s) = atan((mu_s - c) / w),
//   x = (a(mu_s) - a(-1)) / (a(1) - a(-1)).
// mu_h = -sqrt(r^2 - Rb^2) / r, written without the cancellation of
// 1 - (Rb / r)^2 near the ground.
float unit_from_sun_cosine(MultiscatteringMapping m, AtmosphereParameters atm, float r, float mu_s) {
  mu_s = clamp_cosine(mu_s);
  if (m.sun != MULTISCATTERING_SUN_TERMINATOR) return 0.5 + 0.5 * mu_s;
  float rb = atm.bottom_radius;
  r = max(r, rb);
  float centre = -safe_sqrt((r - rb) * (r + rb)) / r - m.offset;
  float a_lo = accurate_atan((-1.0 - centre) / m.width);
  float a_hi = accurate_atan((1.0 - centre) / m.width);
  float x = (accurate_atan((mu_s - centre) / m.width) - a_lo) / (a_hi - a_lo);
  return clamp(x, 0.0, 1.0);
}

// The inverse of the sun axis: mu_s of x_mu_s in [0, 1].
float sun_cosine_from_unit(MultiscatteringMapping m, AtmosphereParameters atm, float r,
                           float x_mu_s) {
  x_mu_s = clamp(x_mu_s, 0.0, 1.0);
  if (m.sun != MULTISCATTERING_SUN_TERMINATOR) return clamp_cosine(2.0 * x_mu_s - 1.0);
  float rb = atm.bottom_radius;
  r = max(r, rb);
  float centre = -safe_sqrt((r - rb) * (r + rb)) / r - m.offset;
  float a_lo = accurate_atan((-1.0 - centre) / m.width);
  float a_hi = accurate_atan((1.0 - centre) / m.width);
  return clamp_cosine(centre + m.width * tan(a_lo + x_mu_s * (a_hi - a_lo)));
}

// x_h in [0, 1] (before texel centring): (r - Rb) / (Rt - Rb), or its
// square root for the quadratic axis (rows at r = Rb + (Rt - Rb) x_h^2,
// docs/reference.md "Multiple scattering"); r clamped to the shell.
float unit_from_radius(MultiscatteringMapping m, AtmosphereParameters atm, float r) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float x = (r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius);
  return m.altitude == MULTISCATTERING_ALTITUDE_QUADRATIC ? sqrt(x) : x;
}

// The inverse of the altitude axis: r of x_h in [0, 1].
float radius_from_unit(MultiscatteringMapping m, AtmosphereParameters atm, float x_h) {
  x_h = clamp(x_h, 0.0, 1.0);
  float x = m.altitude == MULTISCATTERING_ALTITUDE_QUADRATIC ? x_h * x_h : x_h;
  return atm.bottom_radius + x * (atm.top_radius - atm.bottom_radius);
}

// u = coord(x_mu_s, W), v = coord(x_h, H) (Hillaire 2020 sec. 5.5.2 on
// texel centres), r clamped to the shell.
vec2 multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                    int height, MultiscatteringMapping mapping) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float x_mu_s = unit_from_sun_cosine(mapping, atm, r, mu_s);
  float x_h = unit_from_radius(mapping, atm, r);
  return vec2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

// The exact inverse: (r, mu_s) of texture coordinates uv.
vec2 r_mu_s_from_multiscattering_uv(AtmosphereParameters atm, vec2 uv, int width, int height,
                                      MultiscatteringMapping mapping) {
  float r = radius_from_unit(mapping, atm, unit_from_texel_coord(uv.y, height));
  return vec2(r, sun_cosine_from_unit(mapping, atm, r, unit_from_texel_coord(uv.x, width)));
}

// Psi_ms at radius r (clamped to the shell) for a sun of zenith cosine
// mu_s, bilinear, with the table's mapping.
vec3 lookup_multiscattering(sampler2D lut, MultiscatteringMapping mapping, AtmosphereParameters atm,
                            float r, float mu_s) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, multiscattering_uv_from_r_mu_s(atm, r, mu_s, size.x, size.y, mapping), 0.0)
      .rgb;
}

// The same for a table with the linear sun axis (the default).
vec3 lookup_multiscattering(sampler2D lut, AtmosphereParameters atm, float r, float mu_s) {
  return lookup_multiscattering(lut, MultiscatteringMapping(MULTISCATTERING_SUN_LINEAR, 1.0, 0.0,
                                                       MULTISCATTERING_ALTITUDE_LINEAR),
                                atm, r, mu_s);
}

// The terminator mapping with its two constants given directly
// (mu_s_mapping_width, mu_s_mapping_offset of the metadata).
vec2 multiscattering_uv_from_r_mu_s_terminator(AtmosphereParameters atm, float r, float mu_s,
                                               float w, float offset, int width, int height) {
  return multiscattering_uv_from_r_mu_s(
      atm, r, mu_s, width, height,
      MultiscatteringMapping(MULTISCATTERING_SUN_TERMINATOR, w, offset,
                             MULTISCATTERING_ALTITUDE_LINEAR));
}

vec3 lookup_multiscattering_terminator(sampler2D lut, AtmosphereParameters atm, float r,
                                       float mu_s, float w, float offset) {
  return lookup_multiscattering(lut, MultiscatteringMapping(MULTISCATTERING_SUN_TERMINATOR, w, offset,
                             MULTISCATTERING_ALTITUDE_LINEAR),
                                atm, r, mu_s);
}

// requires: atmosphere_common.hlsl
// skybake runtime: the multiple-scattering LUT Psi_ms, HLSL twin of
// runtime/glsl/multiscattering.glsl (Hillaire 2020 sec. 5.5; C++
// src/atmosphere/multiscattering_lut.hpp). RGB linear float, bilinear,
// clamp to edge, no mips (docs/runtime.md "Multiple scattering"); the sun
// axis linear or the terminator mapping of the metadata, the altitude axis
// linear or quadratic.

static const int MULTISCATTERING_SUN_LINEAR = 0;
static const int MULTISCATTERING_SUN_TERMINATOR = 1;
static const int MULTISCATTERING_ALTITUDE_LINEAR = 0;
static const int MULTISCATTERING_ALTITUDE_QUADRATIC = 1;

struct MultiscatteringMapping {
  int sun;       // MULTISCATTERING_SUN_LINEAR or MULTISCATTERING_SUN_TERMINATOR
  float width;   // terminator: w
  float offset;  // terminator: centre below the horizon's cosine
  int altitude;  // MULTISCATTERING_ALTITUDE_LINEAR or MULTISCATTERING_ALTITUDE_QUADRATIC
};

MultiscatteringMapping linear_multiscattering_mapping() {
  MultiscatteringMapping m;
  m.sun = MULTISCATTERING_SUN_LINEAR;
  m.width = 1.0;
  m.offset = 0.0;
  m.altitude = MULTISCATTERING_ALTITUDE_LINEAR;
  return m;
}

// x_mu_s: 0.5 + 0.5 mu_s, or atan around the terminator (see the GLSL).
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

float2 multiscattering_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                      int height, MultiscatteringMapping mapping) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  float x_mu_s = unit_from_sun_cosine(mapping, atm, r, mu_s);
  float x_h = unit_from_radius(mapping, atm, r);
  return float2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_h, height));
}

// The exact inverse: (r, mu_s) of texture coordinates uv.
float2 r_mu_s_from_multiscattering_uv(AtmosphereParameters atm, float2 uv, int width, int height,
                                      MultiscatteringMapping mapping) {
  float r = radius_from_unit(mapping, atm, unit_from_texel_coord(uv.y, height));
  return float2(r, sun_cosine_from_unit(mapping, atm, r, unit_from_texel_coord(uv.x, width)));
}

float3 lookup_multiscattering(Texture2D<float4> lut, SamplerState lut_sampler,
                              MultiscatteringMapping mapping, AtmosphereParameters atm, float r,
                              float mu_s) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         multiscattering_uv_from_r_mu_s(atm, r, mu_s, int(width), int(height),
                                                        mapping), 0.0)
      .rgb;
}

// A table with the linear sun axis (the default).
float3 lookup_multiscattering(Texture2D<float4> lut, SamplerState lut_sampler,
                              AtmosphereParameters atm, float r, float mu_s) {
  return lookup_multiscattering(lut, lut_sampler, linear_multiscattering_mapping(), atm, r, mu_s);
}

// The terminator mapping with its two constants given directly
// (mu_s_mapping_width, mu_s_mapping_offset of the metadata).
MultiscatteringMapping terminator_multiscattering_mapping(float w, float offset) {
  MultiscatteringMapping m;
  m.sun = MULTISCATTERING_SUN_TERMINATOR;
  m.width = w;
  m.offset = offset;
  m.altitude = MULTISCATTERING_ALTITUDE_LINEAR;
  return m;
}

float2 multiscattering_uv_from_r_mu_s_terminator(AtmosphereParameters atm, float r, float mu_s,
                                                 float w, float offset, int width, int height) {
  return multiscattering_uv_from_r_mu_s(atm, r, mu_s, width, height,
                                        terminator_multiscattering_mapping(w, offset));
}

float3 lookup_multiscattering_terminator(Texture2D<float4> lut, SamplerState lut_sampler,
                                         AtmosphereParameters atm, float r, float mu_s, float w,
                                         float offset) {
  return lookup_multiscattering(lut, lut_sampler, terminator_multiscattering_mapping(w, offset),
                                atm, r, mu_s);
}

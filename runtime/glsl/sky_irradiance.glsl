// requires: atmosphere_common.glsl
// skybake runtime: the sky's irradiance E(n) from the sky_irradiance table,
// L2 spherical harmonics of the radiance arriving at an altitude from the
// sky and the lit ground, with the clamped-cosine factors of Ramamoorthi &
// Hanrahan 2001 (eq. 8) applied here, so E(n) is one dot product.
// C++: src/atmosphere/sky_irradiance.hpp; docs/runtime.md "Sky irradiance",
// docs/reference.md "Sky irradiance (L2 SH)".
//
// The texture: sky_irradiance.dds / .ktx2 / .exr, a 2D array of 6 layers,
// RGB linear float; bilinear, clamp to edge; no mips. Bind as
// sampler2DArray. The coefficients L_k of Y_00, Y_10, Y_11, Y_20, Y_21,
// Y_22 in the frame with z up and the sun in the x-z plane (the y-odd
// coefficients are 0 there) are stored as layer 0 = ln L_00, layers 1-5 =
// L_k / L_00: bilinear reads of the logarithm follow the light's
// exponential fall across the terminator. u: sun zenith angle, linear
// from 0 to max_sun_zenith; v: altitude, (v)^2 = altitude / height; texel
// centres at the ends of both axes. Values in units of the sun's
// illuminance (solar_irradiance in the metadata), like the sky-view.

// The table's axes, from its metadata: max_sun_zenith_deg (in radians here)
// and atmosphere_height_m.
struct SkyIrradianceAxes {
  float max_sun_zenith;  // rad
  float height;          // m, top of the atmosphere above the ground
};

// The six coefficients L_k at (altitude, sun zenith): bilinear reads of the
// stored form, decoded.
void sky_irradiance_coefficients(sampler2DArray table, SkyIrradianceAxes axes, float altitude,
                                 float sun_zenith, out vec3 c[6]) {
  vec2 size = vec2(textureSize(table, 0).xy);
  vec2 x = vec2(clamp(sun_zenith / axes.max_sun_zenith, 0.0, 1.0),
                sqrt(clamp(altitude / axes.height, 0.0, 1.0)));
  vec2 uv = (0.5 + x * (size - 1.0)) / size;
  c[0] = exp(textureLod(table, vec3(uv, 0.0), 0.0).rgb);
  for (int j = 1; j < 6; ++j) c[j] = c[0] * textureLod(table, vec3(uv, float(j)), 0.0).rgb;
}

// E(n) for n in the table's frame: sum over k of A_l(k) L_k Y_k(n), with
// A = pi, 2 pi / 3, pi / 4 for bands 0, 1, 2 (R&H 2001 eq. 8) and the real
// SH constants sqrt(1 / 4 pi), sqrt(3 / 4 pi), sqrt(15 / 4 pi),
// sqrt(5 / 16 pi), sqrt(15 / 16 pi).
vec3 sky_irradiance_from_coefficients(vec3 c[6], vec3 n) {
  const float a0 = kPi * 0.28209479177387814;
  const float a1 = (2.0 * kPi / 3.0) * 0.48860251190291992;
  const float a2 = (kPi / 4.0);
  return a0 * c[0] + a1 * (c[1] * n.z + c[2] * n.x) +
         a2 * (0.31539156525252005 * (3.0 * n.z * n.z - 1.0) * c[3] +
               1.0925484305920792 * n.x * n.z * c[4] +
               0.54627421529603959 * (n.x * n.x - n.y * n.y) * c[5]);
}

// The table's frame for a zenith `up` and a sun direction (unit vectors):
// rows x (toward the sun's azimuth), y, z = up.
mat3 sky_irradiance_frame(vec3 up, vec3 sun_dir) {
  vec3 x = sun_dir - dot(up, sun_dir) * up;
  if (dot(x, x) < 1e-12) {  // sun at the zenith or nadir: any x
    x = abs(up.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    x -= dot(x, up) * up;
  }
  x = normalize(x);
  return transpose(mat3(x, cross(up, x), up));
}

// E(n): irradiance on a surface of unit normal n at `altitude` (m above the
// ground), under the zenith `up` and the sun toward sun_dir, any frame.
vec3 sky_irradiance(sampler2DArray table, SkyIrradianceAxes axes, vec3 n, vec3 up, vec3 sun_dir,
                    float altitude) {
  vec3 c[6];
  sky_irradiance_coefficients(table, axes, altitude,
                              accurate_acos(clamp(dot(up, sun_dir), -1.0, 1.0)), c);
  return sky_irradiance_from_coefficients(c, sky_irradiance_frame(up, sun_dir) * n);
}

// A direction d (any frame) in the frame of a sky_environment cube
// (docs/runtime.md "Sky environment": +Y the zenith `up`, +X toward the
// sun's azimuth, +Z = X x Y), to sample the cube with.
vec3 sky_environment_direction(vec3 d, vec3 up, vec3 sun_dir) {
  vec3 s = sky_irradiance_frame(up, sun_dir) * d;
  return vec3(s.x, s.z, -s.y);
}

// Cloud ambient (docs/runtime.md "Cloud ambient"): the mean radiance over the
// sphere, Y_00 L_00, and the mean over the upper hemisphere of the L2
// radiance, Y_00 L_00 + (Y_1 / 2) L_10.
vec3 sky_mean_radiance(sampler2DArray table, SkyIrradianceAxes axes, float altitude,
                       float sun_zenith) {
  vec3 c[6];
  sky_irradiance_coefficients(table, axes, altitude, sun_zenith, c);
  return 0.28209479177387814 * c[0];
}
vec3 sky_mean_upper_radiance(sampler2DArray table, SkyIrradianceAxes axes, float altitude,
                             float sun_zenith) {
  vec3 c[6];
  sky_irradiance_coefficients(table, axes, altitude, sun_zenith, c);
  return 0.28209479177387814 * c[0] + 0.24430125595145996 * c[1];
}

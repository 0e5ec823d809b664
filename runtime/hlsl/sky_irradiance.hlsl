// requires: atmosphere_common.hlsl
// skybake runtime: the sky's irradiance E(n) from the sky_irradiance table,
// HLSL twin of runtime/glsl/sky_irradiance.glsl (Ramamoorthi & Hanrahan
// 2001 eq. 8; C++ src/atmosphere/sky_irradiance.hpp; docs/runtime.md "Sky
// irradiance"). A Texture2DArray of 6 layers, RGB linear float, bilinear,
// clamp to edge, no mips; layer 0 = ln L_00, layers 1-5 = L_k / L_00 for
// Y_10, Y_11, Y_20, Y_21, Y_22, in the frame with z up and the sun in the
// x-z plane.

struct SkyIrradianceAxes {
  float max_sun_zenith;  // rad
  float height;          // m, top of the atmosphere above the ground
};

void sky_irradiance_coefficients(Texture2DArray<float4> table, SamplerState table_sampler,
                                 SkyIrradianceAxes axes, float altitude, float sun_zenith,
                                 out float3 c[6]) {
  uint w, h, layers;
  table.GetDimensions(w, h, layers);
  float2 size = float2(w, h);
  float2 x = float2(clamp(sun_zenith / axes.max_sun_zenith, 0.0, 1.0),
                    sqrt(clamp(altitude / axes.height, 0.0, 1.0)));
  float2 uv = (0.5 + x * (size - 1.0)) / size;
  c[0] = exp(table.SampleLevel(table_sampler, float3(uv, 0.0), 0.0).rgb);
  for (int j = 1; j < 6; ++j) c[j] = c[0] * table.SampleLevel(table_sampler, float3(uv, j), 0.0).rgb;
}

// E(n) for n in the table's frame (see the GLSL).
float3 sky_irradiance_from_coefficients(float3 c[6], float3 n) {
  const float a0 = kPi * 0.28209479177387814;
  const float a1 = (2.0 * kPi / 3.0) * 0.48860251190291992;
  const float a2 = (kPi / 4.0);
  return a0 * c[0] + a1 * (c[1] * n.z + c[2] * n.x) +
         a2 * (0.31539156525252005 * (3.0 * n.z * n.z - 1.0) * c[3] +
               1.0925484305920792 * n.x * n.z * c[4] +
               0.54627421529603959 * (n.x * n.x - n.y * n.y) * c[5]);
}

// Rows x (toward the sun's azimuth), y, z = up of the table's frame.
float3x3 sky_irradiance_frame(float3 up, float3 sun_dir) {
  float3 x = sun_dir - dot(up, sun_dir) * up;
  if (dot(x, x) < 1e-12) {
    x = abs(up.x) < 0.9 ? float3(1.0, 0.0, 0.0) : float3(0.0, 1.0, 0.0);
    x -= dot(x, up) * up;
  }
  x = normalize(x);
  return float3x3(x, cross(up, x), up);
}

float3 sky_irradiance(Texture2DArray<float4> table, SamplerState table_sampler,
                      SkyIrradianceAxes axes, float3 n, float3 up, float3 sun_dir,
                      float altitude) {
  float3 c[6];
  sky_irradiance_coefficients(table, table_sampler, axes, altitude,
                              accurate_acos(clamp(dot(up, sun_dir), -1.0, 1.0)), c);
  return sky_irradiance_from_coefficients(c, mul(sky_irradiance_frame(up, sun_dir), n));
}

// A direction d in the frame of a sky_environment cube (+Y the zenith, +X
// toward the sun's azimuth), to sample the cube with.
float3 sky_environment_direction(float3 d, float3 up, float3 sun_dir) {
  float3 s = mul(sky_irradiance_frame(up, sun_dir), d);
  return float3(s.x, s.z, -s.y);
}

float3 sky_mean_radiance(Texture2DArray<float4> table, SamplerState table_sampler,
                         SkyIrradianceAxes axes, float altitude, float sun_zenith) {
  float3 c[6];
  sky_irradiance_coefficients(table, table_sampler, axes, altitude, sun_zenith, c);
  return 0.28209479177387814 * c[0];
}
float3 sky_mean_upper_radiance(Texture2DArray<float4> table, SamplerState table_sampler,
                               SkyIrradianceAxes axes, float altitude, float sun_zenith) {
  float3 c[6];
  sky_irradiance_coefficients(table, table_sampler, axes, altitude, sun_zenith, c);
  return 0.28209479177387814 * c[0] + 0.24430125595145996 * c[1];
}

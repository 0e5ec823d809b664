// requires: atmosphere_common.hlsl, multiscattering.hlsl
// skybake runtime: the converged model's multiple-scattering source by view,
// HLSL twin of runtime/glsl/multiscattering_view.glsl (docs/reference.md
// "Psi_ms by view"; C++ src/atmosphere/multiscattering_lut.hpp). A volume
// W x H x (1 + nu_slices + zenith_slices), trilinear, clamp on every axis;
// slice 0 isotropic, then a(nu) and b(mu_v), one fetch each (see the GLSL).

float nu_node_unit_from_cosine(float nu) {
  return sqrt(sqrt(clamp(0.5 - 0.5 * nu, 0.0, 1.0)));
}
float zenith_node_unit_from_cosine(float mu_v) {
  mu_v = clamp_cosine(mu_v);
  float s = sqrt(abs(mu_v));
  return 0.5 + 0.5 * (mu_v < 0.0 ? -s : s);
}

float view_slice_w(int first, int nodes, float x, int depth) {
  return (float(first) + clamp(x, 0.0, 1.0) * float(nodes - 1) + 0.5) / float(depth);
}

float3 lookup_multiscattering_view(Texture3D<float4> lut, SamplerState lut_sampler,
                                   MultiscatteringMapping mapping, AtmosphereParameters atm,
                                   int nu_slices, int zenith_slices, float r, float mu_s,
                                   float nu, float mu_v) {
  uint width, height, depth;
  lut.GetDimensions(width, height, depth);
  float2 uv = multiscattering_uv_from_r_mu_s(atm, r, mu_s, int(width), int(height), mapping);
  float w_a = view_slice_w(1, nu_slices, nu_node_unit_from_cosine(nu), int(depth));
  float3 psi = lut.SampleLevel(lut_sampler, float3(uv, w_a), 0.0).rgb;
  if (zenith_slices > 0) {
    float w_b = view_slice_w(1 + nu_slices, zenith_slices, zenith_node_unit_from_cosine(mu_v),
                             int(depth));
    psi += lut.SampleLevel(lut_sampler, float3(uv, w_b), 0.0).rgb;
  }
  return max(psi, float3(0.0, 0.0, 0.0));
}

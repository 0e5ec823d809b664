// requires: atmosphere_common.hlsl
// skybake runtime: the transmittance LUT, HLSL twin of
// runtime/glsl/transmittance.glsl (Hillaire 2020 sec. 5.2; Bruneton 2017
// GetTransmittance; C++ src/atmosphere/transmittance_lut.hpp;
// docs/reference.md "Transmittance"). The texture: RGB linear float,
// bilinear, clamp to edge, no mips (docs/runtime.md "Transmittance").

// The mapping from rho = sqrt(r^2 - Rb^2) and r mu (see the GLSL: a float
// radius resolves 0.5 m near the ground, rho and r mu along a ray do not
// cancel).
float2 transmittance_uv_from_rho_r_mu(AtmosphereParameters atm, float rho, float r_mu, int width,
                                      int height) {
  float rb = atm.bottom_radius, rt = atm.top_radius;
  float H = horizon_distance(atm);
  rho = clamp(rho, 0.0, H);
  float r = sqrt(rho * rho + rb * rb);
  r_mu = clamp(r_mu, -r, r);
  float c = (H - rho) * (H + rho);
  float q = safe_sqrt(c + r_mu * r_mu);
  float d = max(r_mu > 0.0 ? c / max(r_mu + q, 1e-30) : q - r_mu, 0.0);
  float d_min = c / (rt + r), d_max = rho + H;
  float x_mu = clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
  return float2(texel_coord_from_unit(x_mu, width), texel_coord_from_unit(rho / H, height));
}

// The exact inverse (for engines that bake the table themselves): r in
// [Rb, Rt] and mu, 1 where d = 0. Law of cosines, Rt^2 - r^2 = H^2 - rho^2.
void r_mu_from_transmittance_uv(AtmosphereParameters atm, float2 uv, int width, int height,
                                out float r, out float mu) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  float x_mu = clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0);
  float rho = H * clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  r = clamp(sqrt(rho * rho + rb * rb), rb, rt);
  float c = (H - rho) * (H + rho);
  float d_min = c / (rt + r), d_max = rho + H;
  float d = d_min + x_mu * (d_max - d_min);
  mu = d == 0.0 ? 1.0 : clamp_cosine((c - d * d) / (2.0 * r * d));
}

float3 lookup_transmittance_to_top_rho(Texture2D<float4> lut, SamplerState lut_sampler,
                                       AtmosphereParameters atm, float rho, float r_mu) {
  uint width, height;
  lut.GetDimensions(width, height);
  return lut.SampleLevel(lut_sampler,
                         transmittance_uv_from_rho_r_mu(atm, rho, r_mu, int(width), int(height)), 0.0)
      .rgb;
}

// u = coord(x_mu, W), v = coord(rho / H, H_texels); see the GLSL.
float2 transmittance_uv_from_r_mu(AtmosphereParameters atm, float r, float mu, int width, int height) {
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  return transmittance_uv_from_rho_r_mu(atm, safe_sqrt((r - rb) * (r + rb)), r * clamp_cosine(mu),
                                        width, height);
}

float3 lookup_transmittance_to_top(Texture2D<float4> lut, SamplerState lut_sampler,
                                   AtmosphereParameters atm, float r, float mu) {
  uint width, height;
  lut.GetDimensions(width, height);
  float2 uv = transmittance_uv_from_r_mu(atm, r, mu, int(width), int(height));
  return lut.SampleLevel(lut_sampler, uv, 0.0).rgb;
}

// Bruneton 2017 GetTransmittance; 0 where the denominator underflowed. The
// far end by the law of cosines: rho_q^2 = (r - Rb)(r + Rb) + d (2 r mu + d),
// r_q mu_q = r mu + d.
float3 lookup_transmittance(Texture2D<float4> lut, SamplerState lut_sampler,
                            AtmosphereParameters atm, float r, float mu, float d,
                            bool ray_hits_ground) {
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  mu = clamp_cosine(mu);
  float rho = safe_sqrt((r - rb) * (r + rb));
  float rho_d = safe_sqrt((r - rb) * (r + rb) + d * (2.0 * r * mu + d));
  float r_mu = r * mu, r_mu_d = r * mu + d;
  float3 numerator = ray_hits_ground
                         ? lookup_transmittance_to_top_rho(lut, lut_sampler, atm, rho_d, -r_mu_d)
                         : lookup_transmittance_to_top_rho(lut, lut_sampler, atm, rho, r_mu);
  float3 denominator = ray_hits_ground
                           ? lookup_transmittance_to_top_rho(lut, lut_sampler, atm, rho, -r_mu)
                           : lookup_transmittance_to_top_rho(lut, lut_sampler, atm, rho_d, r_mu_d);
  float3 T = float3(0.0, 0.0, 0.0);
  for (int c = 0; c < 3; ++c)
    T[c] = denominator[c] > 0.0 ? min(numerator[c] / denominator[c], 1.0) : 0.0;
  return T;
}

// Toward the sun, times the planet's shadow (Hillaire 2020 eq. 4).
float3 lookup_sun_transmittance(Texture2D<float4> lut, SamplerState lut_sampler,
                                AtmosphereParameters atm, float r, float mu_s) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  mu_s = clamp_cosine(mu_s);
  if (ray_intersects_ground(atm.bottom_radius, r, mu_s)) return float3(0.0, 0.0, 0.0);
  return lookup_transmittance_to_top(lut, lut_sampler, atm, r, mu_s);
}

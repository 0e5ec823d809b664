// requires: atmosphere_common.glsl
// skybake runtime: the transmittance LUT (Hillaire 2020 sec. 5.2, after
// Bruneton & Neyret 2008 sec. 4; mapping and reads after Bruneton 2017
// GetTransmittanceTextureUvFromRMu, GetTransmittanceToTopAtmosphereBoundary,
// GetTransmittance). C++: src/atmosphere/transmittance_lut.hpp,
// sky_integrator.hpp (lookup_sun_transmittance); docs/reference.md
// "Transmittance".
//
// The texture: transmittance.dds / .exr, RGB linear float, bilinear, clamp
// to edge on both axes, no mips (docs/runtime.md "Transmittance"). u runs
// along mu (x_mu = 0 the zenith, 1 the horizon), v along r.

// The same mapping from rho = sqrt(r^2 - Rb^2) and r mu, the quantities it
// depends on. A float radius near Rb = 6.4e6 m resolves 0.5 m, too coarse
// for the altitude of a point near the ground, while rho and r mu of a
// point along a ray come out of the law of cosines without cancellation
// (lookup_transmittance). Rt^2 - r^2 = H^2 - rho^2 and d_min = Rt - r =
// (H^2 - rho^2) / (Rt + r).
vec2 transmittance_uv_from_rho_r_mu(AtmosphereParameters atm, float rho, float r_mu, int width,
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
  return vec2(texel_coord_from_unit(x_mu, width), texel_coord_from_unit(rho / H, height));
}

// The exact inverse (for engines that bake the table themselves): r in
// [Rb, Rt] and mu, 1 where d = 0. Law of cosines, Rt^2 - r^2 = H^2 - rho^2.
void r_mu_from_transmittance_uv(AtmosphereParameters atm, vec2 uv, int width, int height,
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

vec3 lookup_transmittance_to_top_rho(sampler2D lut, AtmosphereParameters atm, float rho,
                                     float r_mu) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, transmittance_uv_from_rho_r_mu(atm, rho, r_mu, size.x, size.y), 0.0).rgb;
}

// Texture coordinates of (r, mu) in a width x height LUT:
//   H = sqrt(Rt^2 - Rb^2), rho = sqrt(r^2 - Rb^2), x_r = rho / H,
//   d = distance to the top, x_mu = (d - d_min) / (d_max - d_min),
//   d_min = Rt - r, d_max = rho + H, u = coord(x_mu, W), v = coord(x_r, H_texels).
// r is clamped to [Rb, Rt]; mu below the horizon reads the horizon column.
vec2 transmittance_uv_from_r_mu(AtmosphereParameters atm, float r, float mu, int width, int height) {
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  return transmittance_uv_from_rho_r_mu(atm, safe_sqrt((r - rb) * (r + rb)), r * clamp_cosine(mu),
                                        width, height);
}

// Transmittance from (r, mu) to the top of the atmosphere, bilinear.
vec3 lookup_transmittance_to_top(sampler2D lut, AtmosphereParameters atm, float r, float mu) {
  ivec2 size = textureSize(lut, 0);
  vec2 uv = transmittance_uv_from_r_mu(atm, r, mu, size.x, size.y);
  return textureLod(lut, uv, 0.0).rgb;
}

// Transmittance between (r, mu) and the point at distance d along the ray
// (Bruneton 2017 GetTransmittance): T(p -> top) / T(q -> top) when the ray
// misses the ground, the ratio of the reversed (upward) rays when it meets
// it. ray_hits_ground = ray_intersects_ground(Rb, r, mu). Where the
// denominator underflowed (optical depth to the top above ~87) the ratio is
// undefined and 0 is returned (docs/reference.md "Transmittance").
vec3 lookup_transmittance(sampler2D lut, AtmosphereParameters atm, float r, float mu, float d,
                          bool ray_hits_ground) {
  // The far end q by the law of cosines: rho_q^2 = r_q^2 - Rb^2 =
  // (r - Rb)(r + Rb) + d (2 r mu + d) and r_q mu_q = r mu + d.
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  mu = clamp_cosine(mu);
  float rho = safe_sqrt((r - rb) * (r + rb));
  float rho_d = safe_sqrt((r - rb) * (r + rb) + d * (2.0 * r * mu + d));
  float r_mu = r * mu, r_mu_d = r * mu + d;
  vec3 numerator = ray_hits_ground ? lookup_transmittance_to_top_rho(lut, atm, rho_d, -r_mu_d)
                                   : lookup_transmittance_to_top_rho(lut, atm, rho, r_mu);
  vec3 denominator = ray_hits_ground ? lookup_transmittance_to_top_rho(lut, atm, rho, -r_mu)
                                     : lookup_transmittance_to_top_rho(lut, atm, rho_d, r_mu_d);
  vec3 T = vec3(0.0);
  for (int c = 0; c < 3; ++c)
    T[c] = denominator[c] > 0.0 ? min(numerator[c] / denominator[c], 1.0) : 0.0;
  return T;
}

// Transmittance toward a sun of zenith cosine mu_s from radius r, times the
// planet's shadow (Hillaire 2020 eq. 4, Vis): 0 when that ray meets the ground.
vec3 lookup_sun_transmittance(sampler2D lut, AtmosphereParameters atm, float r, float mu_s) {
  r = clamp(r, atm.bottom_radius, atm.top_radius);
  mu_s = clamp_cosine(mu_s);
  if (ray_intersects_ground(atm.bottom_radius, r, mu_s)) return vec3(0.0);
  return lookup_transmittance_to_top(lut, atm, r, mu_s);
}

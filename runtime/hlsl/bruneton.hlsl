// requires: atmosphere_common.hlsl, transmittance.hlsl
// skybake runtime: Bruneton's precomputed scattering, HLSL twin of
// runtime/glsl/bruneton.glsl (Bruneton & Neyret 2008 sec. 4; Bruneton 2017
// GetScattering, GetSkyRadiance, GetSunAndSkyIrradiance; C++
// src/atmosphere/scattering_lut.hpp, irradiance_lut.hpp). Samplers
// (docs/runtime.md "Precomputed scattering"): trilinear / bilinear, CLAMP.

struct ScatteringShape {
  int r_size;
  int mu_size;
  int mu_s_size;
  int nu_size;
  float mu_s_min;
};

float scattering_u_from_mu_s(AtmosphereParameters atm, ScatteringShape shape, float mu_s) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  float d_min = rt - rb, d_max = H;
  float A = (distance_to_top_boundary(rt, rb, shape.mu_s_min) - d_min) / (d_max - d_min);
  float d = distance_to_top_boundary(rt, rb, clamp(mu_s, shape.mu_s_min, 1.0));
  float a = (d - d_min) / (d_max - d_min);
  return texel_coord_from_unit(clamp(max(1.0 - a / A, 0.0) / (1.0 + a), 0.0, 1.0), shape.mu_s_size);
}

// The mapping from rho = sqrt(r^2 - Rb^2) and r mu (see the GLSL: a float
// radius resolves 0.5 m near the ground; rho and r mu of a point along a ray
// do not cancel).
float4 scattering_uvwz_from_rho_r_mu(AtmosphereParameters atm, ScatteringShape shape, float rho,
                                     float r_mu, float mu_s, float nu, bool ray_hits_ground) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  rho = clamp(rho, 0.0, H);
  float r = sqrt(rho * rho + rb * rb);
  r_mu = clamp(r_mu, -r, r);
  float u_r = texel_coord_from_unit(rho / H, shape.r_size);
  float u_mu;
  if (ray_hits_ground) {
    float c = rho * rho;
    float d = c / max(safe_sqrt(r_mu * r_mu - c) - r_mu, 1e-30);
    float d_min = c / (r + rb), d_max = rho;
    float x = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
    u_mu = 0.5 - 0.5 * texel_coord_from_unit(clamp(x, 0.0, 1.0), shape.mu_size / 2);
  } else {
    float c = (H - rho) * (H + rho);
    float q = safe_sqrt(c + r_mu * r_mu);
    float d = max(r_mu > 0.0 ? c / max(r_mu + q, 1e-30) : q - r_mu, 0.0);
    float d_min = c / (rt + r), d_max = rho + H;
    float x = (d - d_min) / (d_max - d_min);
    u_mu = 0.5 + 0.5 * texel_coord_from_unit(clamp(x, 0.0, 1.0), shape.mu_size / 2);
  }
  float u_mu_s = scattering_u_from_mu_s(atm, shape, mu_s);
  float u_nu = 0.5 * (clamp_cosine(nu) + 1.0);
  return float4(u_nu, u_mu_s, u_mu, u_r);
}

float4 scattering_uvwz_from_r_mu_mu_s_nu(AtmosphereParameters atm, ScatteringShape shape, float r,
                                         float mu, float mu_s, float nu, bool ray_hits_ground) {
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  return scattering_uvwz_from_rho_r_mu(atm, shape, safe_sqrt((r - rb) * (r + rb)),
                                       r * clamp_cosine(mu), mu_s, nu, ray_hits_ground);
}

// The exact inverse (Bruneton 2017 GetRMuMuSNuFromScatteringTextureUvwz):
// the half of u_mu gives ray_hits_ground; d = 0 gives mu = -1 (ground half)
// or 1 (sky half). nu is not clamped to what mu and mu_s allow.
void r_mu_mu_s_nu_from_scattering_uvwz(AtmosphereParameters atm, ScatteringShape shape, float4 uvwz,
                                       out float r, out float mu, out float mu_s, out float nu,
                                       out bool ray_hits_ground) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  float rho = H * clamp(unit_from_texel_coord(uvwz.w, shape.r_size), 0.0, 1.0);
  r = clamp(sqrt(rho * rho + rb * rb), rb, rt);
  int half_size = shape.mu_size / 2;
  ray_hits_ground = uvwz.z < 0.5;
  if (ray_hits_ground) {
    // Rb^2 = r^2 + d^2 + 2 r d mu, d from r - Rb (down) to rho (the horizon).
    float d_min = rho * rho / (r + rb), d_max = rho;
    float x = clamp(unit_from_texel_coord(1.0 - 2.0 * uvwz.z, half_size), 0.0, 1.0);
    float d = d_min + x * (d_max - d_min);
    mu = d == 0.0 ? -1.0 : clamp_cosine(-(rho * rho + d * d) / (2.0 * r * d));
  } else {
    // Rt^2 = r^2 + d^2 + 2 r d mu, Rt^2 - r^2 = H^2 - rho^2.
    float c = (H - rho) * (H + rho);
    float d_min = c / (rt + r), d_max = rho + H;
    float x = clamp(unit_from_texel_coord(2.0 * uvwz.z - 1.0, half_size), 0.0, 1.0);
    float d = d_min + x * (d_max - d_min);
    mu = d == 0.0 ? 1.0 : clamp_cosine((c - d * d) / (2.0 * r * d));
  }
  float x_mu_s = clamp(unit_from_texel_coord(uvwz.y, shape.mu_s_size), 0.0, 1.0);
  float d_min = rt - rb, d_max = H;
  float A = (distance_to_top_boundary(rt, rb, shape.mu_s_min) - d_min) / (d_max - d_min);
  float a = (A - x_mu_s * A) / (1.0 + x_mu_s * A);
  float d = d_min + min(a, A) * (d_max - d_min);
  mu_s = d == 0.0 ? 1.0 : clamp_cosine((H - d) * (H + d) / (2.0 * rb * d));
  nu = clamp_cosine(2.0 * uvwz.x - 1.0);
}

// Bruneton 2017 GetScattering: the two nu slices blended.
float4 read_scattering(Texture3D<float4> table, SamplerState table_sampler, ScatteringShape shape,
                       float4 uvwz) {
  float x = clamp(uvwz.x, 0.0, 1.0) * float(shape.nu_size - 1);
  float i0 = min(floor(x), float(shape.nu_size - 1));
  float i1 = min(i0 + 1.0, float(shape.nu_size - 1));
  float w = i0 == i1 ? 0.0 : x - i0;
  float n = float(shape.nu_size);
  float4 a = table.SampleLevel(table_sampler, float3((i0 + uvwz.y) / n, uvwz.z, uvwz.w), 0.0);
  float4 b = table.SampleLevel(table_sampler, float3((i1 + uvwz.y) / n, uvwz.z, uvwz.w), 0.0);
  return lerp(a, b, w);
}

float3 lookup_scattering_rgb(Texture3D<float4> table, SamplerState table_sampler,
                             ScatteringShape shape, AtmosphereParameters atm, float r, float mu,
                             float mu_s, float nu, bool ray_hits_ground) {
  return read_scattering(table, table_sampler, shape,
                         scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu,
                                                           ray_hits_ground)).rgb;
}

// Bodare & Sandberg eq. 19, Bruneton 2017 GetExtrapolatedSingleMieScattering.
float3 extrapolated_single_mie(AtmosphereParameters atm, float4 scattering) {
  float3 beta_r = atm.rayleigh_scattering, beta_m = atm.mie_scattering;
  float3 mie = float3(0.0, 0.0, 0.0);
  if (!(scattering.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)) return mie;
  for (int c = 0; c < 3; ++c)
    mie[c] = beta_r[c] > 0.0 ? scattering[c] * (scattering.a / scattering.r) *
                                   (beta_r.r / beta_m.r) * (beta_m[c] / beta_r[c])
                             : 0.0;
  return mie;
}

// p_R(nu) S + p_M(nu) S_M at the table coordinates uvwz, single Mie in its
// own table ...
float3 scattering_radiance_at(Texture3D<float4> scattering, Texture3D<float4> single_mie,
                              SamplerState table_sampler, ScatteringShape shape,
                              AtmosphereParameters atm, float4 uvwz, float nu) {
  float3 rgb = read_scattering(scattering, table_sampler, shape, uvwz).rgb;
  float3 mie = read_scattering(single_mie, table_sampler, shape, uvwz).rgb;
  return rgb * rayleigh_phase(nu) + mie * mie_phase(atm, nu);
}

// ... or in the alpha channel.
float3 scattering_radiance_at(Texture3D<float4> scattering, SamplerState table_sampler,
                              ScatteringShape shape, AtmosphereParameters atm, float4 uvwz,
                              float nu) {
  float4 texel = read_scattering(scattering, table_sampler, shape, uvwz);
  return texel.rgb * rayleigh_phase(nu) + extrapolated_single_mie(atm, texel) * mie_phase(atm, nu);
}

// Single Mie in its own table.
float3 lookup_scattering(Texture3D<float4> scattering, Texture3D<float4> single_mie,
                         SamplerState table_sampler, ScatteringShape shape,
                         AtmosphereParameters atm, float r, float mu, float mu_s, float nu,
                         bool ray_hits_ground) {
  return scattering_radiance_at(
      scattering, single_mie, table_sampler, shape, atm,
      scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground), nu);
}

// Single Mie in the alpha channel.
float3 lookup_scattering(Texture3D<float4> scattering, SamplerState table_sampler,
                         ScatteringShape shape, AtmosphereParameters atm, float r, float mu,
                         float mu_s, float nu, bool ray_hits_ground) {
  return scattering_radiance_at(
      scattering, table_sampler, shape, atm,
      scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground), nu);
}

// ---- Sky radiance for a camera anywhere (Bruneton 2017 GetSkyRadiance,
// GetSkyRadianceToPoint, without light shafts; see the GLSL)

bool move_to_top_atmosphere(AtmosphereParameters atm, inout float3 camera, float3 view_ray,
                            out float r, out float r_mu) {
  r = length(camera);
  r_mu = dot(camera, view_ray);
  if (r <= atm.top_radius) return true;
  float c = (r - atm.top_radius) * (r + atm.top_radius);
  float q = safe_sqrt(r_mu * r_mu - c);
  if (r_mu >= 0.0 || r_mu * r_mu < c) return false;
  float t = c / max(q - r_mu, 1e-30);  // -r mu - q without cancelling
  camera += t * view_ray;
  r = atm.top_radius;  // exactly, rather than the length of the moved float vector
  r_mu += t;
  return true;
}

float3 sky_radiance(Texture3D<float4> scattering, Texture3D<float4> single_mie,
                    SamplerState table_sampler, Texture2D<float4> transmittance_lut,
                    SamplerState transmittance_sampler, ScatteringShape shape,
                    AtmosphereParameters atm, float3 camera, float3 view_ray, float3 sun_dir,
                    out float3 transmittance) {
  transmittance = float3(1.0, 1.0, 1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return float3(0.0, 0.0, 0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = hits ? float3(0.0, 0.0, 0.0)
                       : lookup_transmittance_to_top(transmittance_lut, transmittance_sampler, atm, r, mu);
  return lookup_scattering(scattering, single_mie, table_sampler, shape, atm, r, mu, mu_s,
                           dot(view_ray, sun_dir), hits);
}

float3 sky_radiance(Texture3D<float4> scattering, SamplerState table_sampler,
                    Texture2D<float4> transmittance_lut, SamplerState transmittance_sampler,
                    ScatteringShape shape, AtmosphereParameters atm, float3 camera,
                    float3 view_ray, float3 sun_dir, out float3 transmittance) {
  transmittance = float3(1.0, 1.0, 1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return float3(0.0, 0.0, 0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = hits ? float3(0.0, 0.0, 0.0)
                       : lookup_transmittance_to_top(transmittance_lut, transmittance_sampler, atm, r, mu);
  return lookup_scattering(scattering, table_sampler, shape, atm, r, mu, mu_s,
                           dot(view_ray, sun_dir), hits);
}

// The far end of the segment of length d from (r, mu), through
// rho_p^2 = (r - Rb)(r + Rb) + d (2 r mu + d) and r_p mu_p = r mu + d.
float4 point_uvwz(AtmosphereParameters atm, ScatteringShape shape, float r, float mu, float mu_s,
                  float nu, float d, bool ray_hits_ground) {
  float rb = atm.bottom_radius;
  float rho_p = safe_sqrt((r - rb) * (r + rb) + d * (2.0 * r * mu + d));
  float r_p = clamp(radius_after(r, mu, d), rb, atm.top_radius);
  return scattering_uvwz_from_rho_r_mu(atm, shape, rho_p, r * mu + d, (r * mu_s + d * nu) / r_p, nu,
                                       ray_hits_ground);
}

float3 sky_radiance_to_point(Texture3D<float4> scattering, Texture3D<float4> single_mie,
                             SamplerState table_sampler, Texture2D<float4> transmittance_lut,
                             SamplerState transmittance_sampler, ScatteringShape shape,
                             AtmosphereParameters atm, float3 camera, float3 target,
                             float3 sun_dir, out float3 transmittance) {
  float3 view_ray = normalize(target - camera);
  transmittance = float3(1.0, 1.0, 1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return float3(0.0, 0.0, 0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  float nu = dot(view_ray, sun_dir), d = length(target - camera);
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = lookup_transmittance(transmittance_lut, transmittance_sampler, atm, r, mu, d, hits);
  float4 uvwz_p = point_uvwz(atm, shape, r, mu, mu_s, nu, d, hits);
  return lookup_scattering(scattering, single_mie, table_sampler, shape, atm, r, mu, mu_s, nu, hits) -
         transmittance * scattering_radiance_at(scattering, single_mie, table_sampler, shape, atm,
                                                uvwz_p, nu);
}

float3 sky_radiance_to_point(Texture3D<float4> scattering, SamplerState table_sampler,
                             Texture2D<float4> transmittance_lut,
                             SamplerState transmittance_sampler, ScatteringShape shape,
                             AtmosphereParameters atm, float3 camera, float3 target,
                             float3 sun_dir, out float3 transmittance) {
  float3 view_ray = normalize(target - camera);
  transmittance = float3(1.0, 1.0, 1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return float3(0.0, 0.0, 0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  float nu = dot(view_ray, sun_dir), d = length(target - camera);
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = lookup_transmittance(transmittance_lut, transmittance_sampler, atm, r, mu, d, hits);
  float4 uvwz_p = point_uvwz(atm, shape, r, mu, mu_s, nu, d, hits);
  return lookup_scattering(scattering, table_sampler, shape, atm, r, mu, mu_s, nu, hits) -
         transmittance * scattering_radiance_at(scattering, table_sampler, shape, atm, uvwz_p, nu);
}

// ---- Ground irradiance

float2 irradiance_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                                 int height) {
  float x_r = clamp((r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius), 0.0, 1.0);
  float x_mu_s = 0.5 * clamp_cosine(mu_s) + 0.5;
  return float2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_r, height));
}

// The exact inverse: r = Rb + x_r (Rt - Rb), mu_s = 2 x_mu_s - 1.
void r_mu_s_from_irradiance_uv(AtmosphereParameters atm, float2 uv, int width, int height,
                               out float r, out float mu_s) {
  float x_mu_s = clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0);
  float x_r = clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  r = atm.bottom_radius + x_r * (atm.top_radius - atm.bottom_radius);
  mu_s = clamp_cosine(2.0 * x_mu_s - 1.0);
}

float3 lookup_irradiance(Texture2D<float4> table, SamplerState table_sampler,
                         AtmosphereParameters atm, float r, float mu_s) {
  uint width, height;
  table.GetDimensions(width, height);
  return table.SampleLevel(table_sampler,
                           irradiance_uv_from_r_mu_s(atm, r, mu_s, int(width), int(height)), 0.0)
      .rgb;
}

float sun_average_cosine(float mu_s, float sun_angular_radius) {
  float alpha = sun_angular_radius;
  if (!(alpha > 0.0)) return max(mu_s, 0.0);
  if (mu_s < -alpha) return 0.0;
  if (mu_s > alpha) return mu_s;
  return (mu_s + alpha) * (mu_s + alpha) / (4.0 * alpha);
}

float3 compute_direct_irradiance(AtmosphereParameters atm, Texture2D<float4> transmittance_lut,
                                 SamplerState transmittance_sampler, float r, float mu_s) {
  float c = sun_average_cosine(mu_s, atm.sun_angular_radius);
  if (c == 0.0) return float3(0.0, 0.0, 0.0);
  return atm.sun_illuminance *
         lookup_transmittance_to_top(transmittance_lut, transmittance_sampler, atm, r, mu_s) * c;
}

// Bruneton 2017 GetSunAndSkyIrradiance.
float3 sun_and_sky_irradiance(Texture2D<float4> irradiance_table, SamplerState irradiance_sampler,
                              Texture2D<float4> transmittance_lut,
                              SamplerState transmittance_sampler, AtmosphereParameters atm,
                              float3 position, float3 normal, float3 sun_dir,
                              out float3 sky_irradiance) {
  float r = length(position);
  float3 up = position / r;
  float mu_s = dot(up, sun_dir);
  sky_irradiance = lookup_irradiance(irradiance_table, irradiance_sampler, atm, r, mu_s) *
                   (1.0 + dot(normal, up)) * 0.5;
  return atm.sun_illuminance *
         lookup_sun_transmittance(transmittance_lut, transmittance_sampler, atm, r, mu_s) *
         max(dot(normal, sun_dir), 0.0);
}

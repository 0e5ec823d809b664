// requires: atmosphere_common.hlsl
// skybake runtime: the azimuth-free 3D table and its gathering LUT, HLSL twin
// of runtime/glsl/scattering3d.glsl (Hillaire 2016 Appendix A; Bodare &
// Sandberg 2014 ch. 4; C++ src/atmosphere/scattering3d_lut.hpp,
// gathering_lut.hpp). Samplers (docs/runtime.md "Azimuth-free 3D
// scattering"): trilinear / bilinear, CLAMP.

struct Scattering3dShape {
  int height_size;
  int view_size;
  int sun_size;
};

static const float kScattering3dMuSMin = -0.44807578;
static const float kScattering3dSunScale = 1.3837077;  // tan(1.26 * 0.75)

float scattering3d_u_from_h(AtmosphereParameters atm, float h, int n) {
  float thickness = atm.top_radius - atm.bottom_radius;
  return texel_coord_from_unit(sqrt(clamp(h / thickness, 0.0, 1.0)), n);
}

float scattering3d_u_from_mu_s(float mu_s, int n) {
  float m = clamp(mu_s, kScattering3dMuSMin, 1.0);
  float x = 0.5 * (accurate_atan(m * kScattering3dSunScale) / 0.75 + (1.0 - 0.26));
  return texel_coord_from_unit(clamp(x, 0.0, 1.0), n);
}

float horizon_cosine(AtmosphereParameters atm, float h) {
  h = max(h, 0.0);
  return -sqrt(h * (2.0 * atm.bottom_radius + h)) / (atm.bottom_radius + h);
}

float scattering3d_u_from_mu(AtmosphereParameters atm, float h, float mu, bool ray_hits_ground,
                             int n) {
  float mu_h = horizon_cosine(atm, h);
  int half_n = n / 2;
  if (!ray_hits_ground) {
    float x = pow(clamp((mu - mu_h) / (1.0 - mu_h), 0.0, 1.0), 0.2);
    return 0.5 + 0.5 * texel_coord_from_unit(x, half_n);
  }
  float x = pow(clamp((mu_h - mu) / (mu_h + 1.0), 0.0, 1.0), 0.2);
  return 0.5 * texel_coord_from_unit(x, half_n);
}

float3 scattering3d_uvw_from_h_mu_mu_s(AtmosphereParameters atm, Scattering3dShape shape, float h,
                                       float mu, float mu_s, bool ray_hits_ground) {
  return float3(scattering3d_u_from_h(atm, h, shape.height_size),
                scattering3d_u_from_mu(atm, h, mu, ray_hits_ground, shape.view_size),
                scattering3d_u_from_mu_s(mu_s, shape.sun_size));
}

// The exact inverses of the three axes (h = x^2 H_atm; mu_s = tan((2x - 1
// + 0.26) 0.75) / tan(1.26 * 0.75); mu from the fifth power on each side of
// the horizon, the half giving ray_hits_ground).
float h_from_scattering3d_u(AtmosphereParameters atm, float u, int n) {
  float x = clamp(unit_from_texel_coord(u, n), 0.0, 1.0);
  return x * x * (atm.top_radius - atm.bottom_radius);
}

float mu_s_from_scattering3d_u(float u, int n) {
  float x = clamp(unit_from_texel_coord(u, n), 0.0, 1.0);
  return clamp_cosine(tan((2.0 * x - 1.0 + 0.26) * 0.75) / kScattering3dSunScale);
}

float mu_from_scattering3d_u(AtmosphereParameters atm, float h, float u, int n,
                             out bool ray_hits_ground) {
  float mu_h = horizon_cosine(atm, h);
  int half_n = n / 2;
  ray_hits_ground = u < 0.5;
  if (!ray_hits_ground) {
    float x = clamp(unit_from_texel_coord(2.0 * u - 1.0, half_n), 0.0, 1.0);
    return clamp_cosine(mu_h + pow(x, 5.0) * (1.0 - mu_h));
  }
  float x = clamp(unit_from_texel_coord(2.0 * u, half_n), 0.0, 1.0);
  return clamp_cosine(mu_h - pow(x, 5.0) * (mu_h + 1.0));
}

void h_mu_mu_s_from_scattering3d_uvw(AtmosphereParameters atm, Scattering3dShape shape, float3 uvw,
                                     out float h, out float mu, out float mu_s,
                                     out bool ray_hits_ground) {
  h = h_from_scattering3d_u(atm, uvw.x, shape.height_size);
  mu = mu_from_scattering3d_u(atm, h, uvw.y, shape.view_size, ray_hits_ground);
  mu_s = mu_s_from_scattering3d_u(uvw.z, shape.sun_size);
}

float4 lookup_scattering3d_rgba(Texture3D<float4> table, SamplerState table_sampler,
                                Scattering3dShape shape, AtmosphereParameters atm, float h,
                                float mu, float mu_s, bool ray_hits_ground) {
  return table.SampleLevel(table_sampler,
                           scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, mu_s, ray_hits_ground),
                           0.0);
}

// S_M in its own table.
float3 lookup_scattering3d(Texture3D<float4> scattering, Texture3D<float4> mie,
                           SamplerState table_sampler, Scattering3dShape shape,
                           AtmosphereParameters atm, float h, float mu, float mu_s, float nu,
                           bool ray_hits_ground) {
  float3 uvw = scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, mu_s, ray_hits_ground);
  float3 rgb = scattering.SampleLevel(table_sampler, uvw, 0.0).rgb;
  float3 m = mie.SampleLevel(table_sampler, uvw, 0.0).rgb;
  return rgb * rayleigh_phase(nu) + m * mie_phase(atm, nu);
}

// S_M.r in the alpha channel (Bodare & Sandberg eq. 19).
float3 lookup_scattering3d(Texture3D<float4> scattering, SamplerState table_sampler,
                           Scattering3dShape shape, AtmosphereParameters atm, float h, float mu,
                           float mu_s, float nu, bool ray_hits_ground) {
  float4 texel = lookup_scattering3d_rgba(scattering, table_sampler, shape, atm, h, mu, mu_s,
                                          ray_hits_ground);
  float3 beta_r = atm.rayleigh_scattering, beta_m = atm.mie_scattering;
  float3 m = float3(0.0, 0.0, 0.0);
  if (texel.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)
    for (int c = 0; c < 3; ++c)
      m[c] = beta_r[c] > 0.0 ? texel[c] * (texel.a / texel.r) * (beta_r.r / beta_m.r) *
                                   (beta_m[c] / beta_r[c])
                             : 0.0;
  return texel.rgb * rayleigh_phase(nu) + m * mie_phase(atm, nu);
}

// ---- The gathering LUT

float3 lookup_gathering(Texture2D<float4> gathering, SamplerState gathering_sampler,
                        AtmosphereParameters atm, float h, float mu_s) {
  uint width, height;
  gathering.GetDimensions(width, height);
  return gathering.SampleLevel(gathering_sampler,
                               float2(scattering3d_u_from_h(atm, h, int(width)),
                                      scattering3d_u_from_mu_s(mu_s, int(height))), 0.0).rgb;
}

// Bodare & Sandberg sec. 6.4: multiple scattering per metre of path.
float3 gathered_inscattering(AtmosphereParameters atm, float3 gathered, float3 sigma_s_rayleigh,
                             float3 sigma_s_mie, float nu) {
  return (sigma_s_rayleigh * rayleigh_phase(nu) + sigma_s_mie * mie_phase(atm, nu)) * gathered;
}

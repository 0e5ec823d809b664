// requires: atmosphere_common.glsl
// skybake runtime: the azimuth-free 3D scattering table (Elek 2009 as used
// in Frostbite, Hillaire 2016 sec. 3.5 and Appendix A; Bodare & Sandberg
// 2014 ch. 4) and its gathering LUT (Bodare & Sandberg sec. 4.7.3).
// C++: src/atmosphere/scattering3d_lut.hpp (lookup_scattering3d),
// gathering_lut.hpp (lookup_gathering); docs/reference.md "The azimuth-free
// 3D table and the gathering LUT".
//
// The textures (docs/runtime.md "Azimuth-free 3D scattering"):
// - scattering3d.dds: a volume, x = altitude, y = view zenith cosine, z =
//   sun zenith cosine; RGB phase-free Rayleigh (+ A = Mie's red channel, the
//   default) linear float; trilinear, clamp to edge; no mips.
// - scattering3d_mie.dds (mie: separate): the same shape, RGB.
// - gathering_sum.dds: 2D, x = altitude, y = sun zenith cosine, RGB; bilinear,
//   clamp to edge; no mips.

struct Scattering3dShape {
  int height_size;  // texels along h (texture width)
  int view_size;    // texels along mu (texture height), even
  int sun_size;     // texels along mu_s (texture depth)
};

// tan(-0.74 * 0.75) / tan(1.26 * 0.75): the mu_s of x = 0 on the sun axis.
const float kScattering3dMuSMin = -0.44807578;
const float kScattering3dSunScale = 1.3837077;  // tan(1.26 * 0.75)

// u_h = coord(sqrt(h / H_atm), n) (Bodare & Sandberg eq. 16).
float scattering3d_u_from_h(AtmosphereParameters atm, float h, int n) {
  float thickness = atm.top_radius - atm.bottom_radius;
  return texel_coord_from_unit(sqrt(clamp(h / thickness, 0.0, 1.0)), n);
}

// u_s = coord(0.5 (atan(max(mu_s, mu_s_min) tan(1.26 * 0.75)) / 0.75 + 0.74), n)
// (Hillaire 2016 Appendix A, Listing 4; Bodare & Sandberg eq. 18 with 0.75).
float scattering3d_u_from_mu_s(float mu_s, int n) {
  float m = clamp(mu_s, kScattering3dMuSMin, 1.0);
  float x = 0.5 * (accurate_atan(m * kScattering3dSunScale) / 0.75 + (1.0 - 0.26));
  return texel_coord_from_unit(clamp(x, 0.0, 1.0), n);
}

// The horizon's zenith cosine at altitude h, -sqrt(h (2 Rb + h)) / (Rb + h).
float horizon_cosine(AtmosphereParameters atm, float h) {
  h = max(h, 0.0);
  return -sqrt(h * (2.0 * atm.bottom_radius + h)) / (atm.bottom_radius + h);
}

// u_mu, two halves split at the horizon (Bodare & Sandberg eq. 17):
//   sky:    0.5 + 0.5 coord(((mu - mu_h) / (1 - mu_h))^0.2, n / 2)
//   ground: 0.5 coord(((mu_h - mu) / (mu_h + 1))^0.2, n / 2)
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

vec3 scattering3d_uvw_from_h_mu_mu_s(AtmosphereParameters atm, Scattering3dShape shape, float h,
                                     float mu, float mu_s, bool ray_hits_ground) {
  return vec3(scattering3d_u_from_h(atm, h, shape.height_size),
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

void h_mu_mu_s_from_scattering3d_uvw(AtmosphereParameters atm, Scattering3dShape shape, vec3 uvw,
                                     out float h, out float mu, out float mu_s,
                                     out bool ray_hits_ground) {
  h = h_from_scattering3d_u(atm, uvw.x, shape.height_size);
  mu = mu_from_scattering3d_u(atm, h, uvw.y, shape.view_size, ray_hits_ground);
  mu_s = mu_s_from_scattering3d_u(uvw.z, shape.sun_size);
}

// Trilinear read of the four channels at (h, mu, mu_s), no phase.
vec4 lookup_scattering3d_rgba(sampler3D table, Scattering3dShape shape, AtmosphereParameters atm,
                              float h, float mu, float mu_s, bool ray_hits_ground) {
  return textureLod(table, scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, mu_s, ray_hits_ground),
                    0.0);
}

// Radiance p_R(nu) S_R + p_M(nu) S_M toward a viewer at altitude h looking
// along mu, the phases applied here (Bodare & Sandberg sec. 4.1); S_M from
// its own table.
vec3 lookup_scattering3d(sampler3D scattering, sampler3D mie, Scattering3dShape shape,
                         AtmosphereParameters atm, float h, float mu, float mu_s, float nu,
                         bool ray_hits_ground) {
  vec3 uvw = scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, mu_s, ray_hits_ground);
  vec3 rgb = textureLod(scattering, uvw, 0.0).rgb;
  vec3 m = textureLod(mie, uvw, 0.0).rgb;
  return rgb * rayleigh_phase(nu) + m * mie_phase(atm, nu);
}

// The same with S_M.r in the alpha channel (Bodare & Sandberg eq. 19: the
// other channels follow Rayleigh's ratios scaled by the coefficients).
vec3 lookup_scattering3d(sampler3D scattering, Scattering3dShape shape, AtmosphereParameters atm,
                         float h, float mu, float mu_s, float nu, bool ray_hits_ground) {
  vec4 texel = lookup_scattering3d_rgba(scattering, shape, atm, h, mu, mu_s, ray_hits_ground);
  vec3 beta_r = atm.rayleigh_scattering, beta_m = atm.mie_scattering;
  vec3 m = vec3(0.0);
  if (texel.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)
    for (int c = 0; c < 3; ++c)
      m[c] = beta_r[c] > 0.0 ? texel[c] * (texel.a / texel.r) * (beta_r.r / beta_m.r) *
                                   (beta_m[c] / beta_r[c])
                             : 0.0;
  return texel.rgb * rayleigh_phase(nu) + m * mie_phase(atm, nu);
}

// ---- The gathering LUT -----------------------------------------------------------

// G(h, mu_s) = int over 4 pi of the light of the orders it sums (radiance x sr),
// bilinear on the 3D table's h and mu_s axes.
vec3 lookup_gathering(sampler2D gathering, AtmosphereParameters atm, float h, float mu_s) {
  ivec2 size = textureSize(gathering, 0);
  return textureLod(gathering, vec2(scattering3d_u_from_h(atm, h, size.x),
                                    scattering3d_u_from_mu_s(mu_s, size.y)), 0.0).rgb;
}

// Multiple scattering toward the viewer per metre of path at a point with
// Rayleigh and Mie scattering coefficients sigma_s_rayleigh, sigma_s_mie
// (1/m): p_R(nu) sigma_R G + p_M(nu) sigma_M G, the integrand of Bodare &
// Sandberg sec. 6.4 (gathering_sum: orders 2..N; integrate it times the
// view ray's transmittance along the path, as aerial perspective does).
vec3 gathered_inscattering(AtmosphereParameters atm, vec3 gathered, vec3 sigma_s_rayleigh,
                           vec3 sigma_s_mie, float nu) {
  return (sigma_s_rayleigh * rayleigh_phase(nu) + sigma_s_mie * mie_phase(atm, nu)) * gathered;
}

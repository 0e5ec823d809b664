// requires: atmosphere_common.glsl, transmittance.glsl
// skybake runtime: Bruneton's precomputed scattering (Bruneton & Neyret 2008
// sec. 4, in the layout and with the reads of Bruneton 2017
// atmosphere/functions.glsl): sky radiance from the 4D table, its single
// Mie part from a separate table or from the alpha channel, and ground
// irradiance. C++: src/atmosphere/scattering_lut.hpp (lookup_scattering),
// irradiance_lut.hpp (lookup_irradiance, compute_direct_irradiance);
// docs/reference.md "Precomputed scattering", "Ground irradiance".
//
// The textures (docs/runtime.md "Precomputed scattering"):
// - scattering.dds: a volume of width nu_size * mu_s_size, height mu_size,
//   depth r_size; RGB (RGBA with Mie in alpha) linear float; trilinear,
//   clamp to edge on every axis; no mips. The nu axis is blended here.
// - single_mie.dds: the same shape, RGB; same sampler.
// - irradiance.dds: 2D, RGB; bilinear, clamp to edge; no mips. By default
//   the indirect part only: add compute_direct_irradiance.

// The table's shape (manifest / metadata: r_size, mu_size, mu_s_size,
// nu_size, mu_s_min).
struct ScatteringShape {
  int r_size;      // texels along r (texture depth)
  int mu_size;     // texels along mu (texture height), even
  int mu_s_size;   // texels along mu_s
  int nu_size;     // slices along nu
  float mu_s_min;  // lowest sun zenith cosine (cos 102 deg by default)
};

// u_mu_s: the distance from the ground to the top along mu_s, a = (d - d_min)
// / (d_max - d_min) with d_min = Rt - Rb, d_max = H; A = a(mu_s_min);
// x = max(1 - a / A, 0) / (1 + a) (Bruneton 2017
// GetScatteringTextureUvwzFromRMuMuSNu).
float scattering_u_from_mu_s(AtmosphereParameters atm, ScatteringShape shape, float mu_s) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  float d_min = rt - rb, d_max = H;
  float A = (distance_to_top_boundary(rt, rb, shape.mu_s_min) - d_min) / (d_max - d_min);
  float d = distance_to_top_boundary(rt, rb, clamp(mu_s, shape.mu_s_min, 1.0));
  float a = (d - d_min) / (d_max - d_min);
  return texel_coord_from_unit(clamp(max(1.0 - a / A, 0.0) / (1.0 + a), 0.0, 1.0), shape.mu_s_size);
}

// The same mapping from rho = sqrt(r^2 - Rb^2) and r mu, which the u_r and
// u_mu of the mapping depend on: r^2 - Rb^2 = rho^2, Rt^2 - r^2 = H^2 - rho^2,
// r - Rb = rho^2 / (r + Rb). A float radius resolves 0.5 m near Earth's
// ground, where rho spans a few km; rho and r mu of a point along a ray
// come out of the law of cosines without that loss (sky_radiance_to_point).
vec4 scattering_uvwz_from_rho_r_mu(AtmosphereParameters atm, ScatteringShape shape, float rho,
                                   float r_mu, float mu_s, float nu, bool ray_hits_ground) {
  float rb = atm.bottom_radius, rt = atm.top_radius, H = horizon_distance(atm);
  rho = clamp(rho, 0.0, H);
  float r = sqrt(rho * rho + rb * rb);
  r_mu = clamp(r_mu, -r, r);
  float u_r = texel_coord_from_unit(rho / H, shape.r_size);
  float u_mu;
  if (ray_hits_ground) {
    float c = rho * rho;
    float d = c / max(safe_sqrt(r_mu * r_mu - c) - r_mu, 1e-30);  // distance to the ground
    float d_min = c / (r + rb), d_max = rho;
    float x = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
    u_mu = 0.5 - 0.5 * texel_coord_from_unit(clamp(x, 0.0, 1.0), shape.mu_size / 2);
  } else {
    float c = (H - rho) * (H + rho);
    float q = safe_sqrt(c + r_mu * r_mu);
    float d = max(r_mu > 0.0 ? c / max(r_mu + q, 1e-30) : q - r_mu, 0.0);  // distance to the top
    float d_min = c / (rt + r), d_max = rho + H;
    float x = (d - d_min) / (d_max - d_min);
    u_mu = 0.5 + 0.5 * texel_coord_from_unit(clamp(x, 0.0, 1.0), shape.mu_size / 2);
  }
  float u_mu_s = scattering_u_from_mu_s(atm, shape, mu_s);
  float u_nu = 0.5 * (clamp_cosine(nu) + 1.0);
  return vec4(u_nu, u_mu_s, u_mu, u_r);
}

// (u_nu, u_mu_s, u_mu, u_r) of (r, mu, mu_s, nu); ray_hits_ground picks the
// half of the mu axis (ray_intersects_ground(Rb, r, mu) for a ray inside):
//   u_r  = coord(rho / H, r_size)
//   u_mu = ground: 0.5 - 0.5 coord((d - (r - Rb)) / (rho - (r - Rb)), mu_size / 2), d to the ground
//          sky:    0.5 + 0.5 coord((d - (Rt - r)) / (rho + H - (Rt - r)), mu_size / 2), d to the top
//   u_nu = (nu + 1) / 2, slices at nu = -1 + 2 k / (nu_size - 1).
vec4 scattering_uvwz_from_r_mu_mu_s_nu(AtmosphereParameters atm, ScatteringShape shape, float r,
                                       float mu, float mu_s, float nu, bool ray_hits_ground) {
  float rb = atm.bottom_radius;
  r = clamp(r, rb, atm.top_radius);
  return scattering_uvwz_from_rho_r_mu(atm, shape, safe_sqrt((r - rb) * (r + rb)),
                                       r * clamp_cosine(mu), mu_s, nu, ray_hits_ground);
}

// The exact inverse (Bruneton 2017 GetRMuMuSNuFromScatteringTextureUvwz):
// the half of u_mu gives ray_hits_ground; d = 0 gives mu = -1 (ground half)
// or 1 (sky half). nu is not clamped to what mu and mu_s allow.
void r_mu_mu_s_nu_from_scattering_uvwz(AtmosphereParameters atm, ScatteringShape shape, vec4 uvwz,
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

// The 4D read (Bruneton 2017 GetScattering): trilinear within the two nu
// slices around u_nu, blended linearly between them. Slice k spans
// x in [k, k + 1) / nu_size of the texture; u_mu_s stays on its texel
// centres, so the hardware's filter never mixes two slices.
vec4 read_scattering(sampler3D table, ScatteringShape shape, vec4 uvwz) {
  float x = clamp(uvwz.x, 0.0, 1.0) * float(shape.nu_size - 1);
  float i0 = min(floor(x), float(shape.nu_size - 1));
  float i1 = min(i0 + 1.0, float(shape.nu_size - 1));
  float w = i0 == i1 ? 0.0 : x - i0;
  float n = float(shape.nu_size);
  vec4 a = textureLod(table, vec3((i0 + uvwz.y) / n, uvwz.z, uvwz.w), 0.0);
  vec4 b = textureLod(table, vec3((i1 + uvwz.y) / n, uvwz.z, uvwz.w), 0.0);
  return mix(a, b, w);
}

// Channels 0..2 of the table at (r, mu, mu_s, nu), no phase.
vec3 lookup_scattering_rgb(sampler3D table, ScatteringShape shape, AtmosphereParameters atm,
                           float r, float mu, float mu_s, float nu, bool ray_hits_ground) {
  return read_scattering(table, shape,
                         scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu,
                                                           ray_hits_ground)).rgb;
}

// Single Mie from a combined RGBA texel (Bodare & Sandberg eq. 19, Bruneton
// 2017 GetExtrapolatedSingleMieScattering): alpha holds S_M.r, and the other
// channels follow Rayleigh's ratios scaled by the groups' coefficients:
//   mie = rgb (alpha / rgb.r) (beta_R.r / beta_M.r) (beta_M / beta_R).
vec3 extrapolated_single_mie(AtmosphereParameters atm, vec4 scattering) {
  vec3 beta_r = atm.rayleigh_scattering, beta_m = atm.mie_scattering;
  if (!(scattering.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)) return vec3(0.0);
  vec3 mie = vec3(0.0);
  for (int c = 0; c < 3; ++c)
    mie[c] = beta_r[c] > 0.0 ? scattering[c] * (scattering.a / scattering.r) *
                                   (beta_r.r / beta_m.r) * (beta_m[c] / beta_r[c])
                             : 0.0;
  return mie;
}

// p_R(nu) S + p_M(nu) S_M at the table coordinates uvwz (the phases deferred
// to here, Bruneton 2017 GetSkyRadiance), single Mie in its own table ...
vec3 scattering_radiance_at(sampler3D scattering, sampler3D single_mie, ScatteringShape shape,
                            AtmosphereParameters atm, vec4 uvwz, float nu) {
  vec3 rgb = read_scattering(scattering, shape, uvwz).rgb;
  vec3 mie = read_scattering(single_mie, shape, uvwz).rgb;
  return rgb * rayleigh_phase(nu) + mie * mie_phase(atm, nu);
}

// ... or in the alpha channel of `scattering` (mie: alpha).
vec3 scattering_radiance_at(sampler3D scattering, ScatteringShape shape, AtmosphereParameters atm,
                            vec4 uvwz, float nu) {
  vec4 texel = read_scattering(scattering, shape, uvwz);
  return texel.rgb * rayleigh_phase(nu) + extrapolated_single_mie(atm, texel) * mie_phase(atm, nu);
}

// Sky radiance toward a viewer at (r, mu), single Mie in its own table.
vec3 lookup_scattering(sampler3D scattering, sampler3D single_mie, ScatteringShape shape,
                       AtmosphereParameters atm, float r, float mu, float mu_s, float nu,
                       bool ray_hits_ground) {
  return scattering_radiance_at(
      scattering, single_mie, shape, atm,
      scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground), nu);
}

// The same with single Mie in the alpha channel of `scattering` (mie: alpha).
vec3 lookup_scattering(sampler3D scattering, ScatteringShape shape, AtmosphereParameters atm,
                       float r, float mu, float mu_s, float nu, bool ray_hits_ground) {
  return scattering_radiance_at(
      scattering, shape, atm,
      scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground), nu);
}

// ---- Sky radiance for a camera anywhere ---------------------------------------
// Bruneton 2017 GetSkyRadiance and GetSkyRadianceToPoint (without light
// shafts): positions planet-centred in m, directions unit. A camera above
// the atmosphere reads the table where its ray enters the top; a ray that
// misses the atmosphere sees nothing (transmittance 1).

// The camera moved to where view_ray enters the atmosphere, with its radius
// r and r mu there (Bruneton 2017 GetSkyRadiance); false when the ray
// misses the atmosphere.
bool move_to_top_atmosphere(AtmosphereParameters atm, inout vec3 camera, vec3 view_ray,
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

// Radiance toward the camera along view_ray from the whole atmosphere
// behind it (the sky, or the air in front of the ground), and the
// transmittance to the top (0 when the ray meets the ground).
vec3 sky_radiance(sampler3D scattering, sampler3D single_mie, sampler2D transmittance_lut,
                  ScatteringShape shape, AtmosphereParameters atm, vec3 camera, vec3 view_ray,
                  vec3 sun_dir, out vec3 transmittance) {
  transmittance = vec3(1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return vec3(0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = hits ? vec3(0.0) : lookup_transmittance_to_top(transmittance_lut, atm, r, mu);
  return lookup_scattering(scattering, single_mie, shape, atm, r, mu, mu_s, dot(view_ray, sun_dir),
                           hits);
}

// The same with single Mie in the alpha channel of `scattering`.
vec3 sky_radiance(sampler3D scattering, sampler2D transmittance_lut, ScatteringShape shape,
                  AtmosphereParameters atm, vec3 camera, vec3 view_ray, vec3 sun_dir,
                  out vec3 transmittance) {
  transmittance = vec3(1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return vec3(0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = hits ? vec3(0.0) : lookup_transmittance_to_top(transmittance_lut, atm, r, mu);
  return lookup_scattering(scattering, shape, atm, r, mu, mu_s, dot(view_ray, sun_dir), hits);
}

// The table coordinates of the far end of the segment of length d from
// (r, mu), the sun fixed (Bruneton 2017 GetSkyRadianceToPoint), through
// rho_p^2 = (r - Rb)(r + Rb) + d (2 r mu + d) and r_p mu_p = r mu + d.
vec4 point_uvwz(AtmosphereParameters atm, ScatteringShape shape, float r, float mu, float mu_s,
                float nu, float d, bool ray_hits_ground) {
  float rb = atm.bottom_radius;
  float rho_p = safe_sqrt((r - rb) * (r + rb) + d * (2.0 * r * mu + d));
  float r_p = clamp(radius_after(r, mu, d), rb, atm.top_radius);
  return scattering_uvwz_from_rho_r_mu(atm, shape, rho_p, r * mu + d, (r * mu_s + d * nu) / r_p, nu,
                                       ray_hits_ground);
}

// Radiance scattered toward the camera between it and `point` (aerial
// perspective from the 4D table): S(camera) - T(camera, point) S(point),
// and the transmittance T of that segment. Bruneton's demo also fades
// single Mie with smoothstep(0, 0.01, mu_s) to hide the subtraction's
// artefacts with the sun below the horizon; add it where they show.
vec3 sky_radiance_to_point(sampler3D scattering, sampler3D single_mie, sampler2D transmittance_lut,
                           ScatteringShape shape, AtmosphereParameters atm, vec3 camera, vec3 point,
                           vec3 sun_dir, out vec3 transmittance) {
  vec3 view_ray = normalize(point - camera);
  transmittance = vec3(1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return vec3(0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  float nu = dot(view_ray, sun_dir), d = length(point - camera);
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = lookup_transmittance(transmittance_lut, atm, r, mu, d, hits);
  vec4 uvwz_p = point_uvwz(atm, shape, r, mu, mu_s, nu, d, hits);
  return lookup_scattering(scattering, single_mie, shape, atm, r, mu, mu_s, nu, hits) -
         transmittance * scattering_radiance_at(scattering, single_mie, shape, atm, uvwz_p, nu);
}

vec3 sky_radiance_to_point(sampler3D scattering, sampler2D transmittance_lut, ScatteringShape shape,
                           AtmosphereParameters atm, vec3 camera, vec3 point, vec3 sun_dir,
                           out vec3 transmittance) {
  vec3 view_ray = normalize(point - camera);
  transmittance = vec3(1.0);
  float r, r_mu;
  if (!move_to_top_atmosphere(atm, camera, view_ray, r, r_mu)) return vec3(0.0);
  float mu = r_mu / r, mu_s = dot(camera, sun_dir) / r;
  float nu = dot(view_ray, sun_dir), d = length(point - camera);
  bool hits = ray_intersects_ground(atm.bottom_radius, r, mu);
  transmittance = lookup_transmittance(transmittance_lut, atm, r, mu, d, hits);
  vec4 uvwz_p = point_uvwz(atm, shape, r, mu, mu_s, nu, d, hits);
  return lookup_scattering(scattering, shape, atm, r, mu, mu_s, nu, hits) -
         transmittance * scattering_radiance_at(scattering, shape, atm, uvwz_p, nu);
}

// ---- Ground irradiance ----------------------------------------------------------

// u = coord(0.5 + 0.5 mu_s, W), v = coord((r - Rb) / (Rt - Rb), H).
vec2 irradiance_uv_from_r_mu_s(AtmosphereParameters atm, float r, float mu_s, int width,
                               int height) {
  float x_r = clamp((r - atm.bottom_radius) / (atm.top_radius - atm.bottom_radius), 0.0, 1.0);
  float x_mu_s = 0.5 * clamp_cosine(mu_s) + 0.5;
  return vec2(texel_coord_from_unit(x_mu_s, width), texel_coord_from_unit(x_r, height));
}

// The exact inverse: r = Rb + x_r (Rt - Rb), mu_s = 2 x_mu_s - 1.
void r_mu_s_from_irradiance_uv(AtmosphereParameters atm, vec2 uv, int width, int height,
                               out float r, out float mu_s) {
  float x_mu_s = clamp(unit_from_texel_coord(uv.x, width), 0.0, 1.0);
  float x_r = clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  r = atm.bottom_radius + x_r * (atm.top_radius - atm.bottom_radius);
  mu_s = clamp_cosine(2.0 * x_mu_s - 1.0);
}

// The table's irradiance on a horizontal surface at radius r for a sun at
// mu_s, bilinear (indirect only unless the bake summed the direct part in).
vec3 lookup_irradiance(sampler2D table, AtmosphereParameters atm, float r, float mu_s) {
  ivec2 size = textureSize(table, 0);
  return textureLod(table, irradiance_uv_from_r_mu_s(atm, r, mu_s, size.x, size.y), 0.0).rgb;
}

// The cosine factor averaged over the sun's disk of angular radius alpha: 0
// below -alpha, mu_s above alpha, (mu_s + alpha)^2 / (4 alpha) between
// (Bruneton 2017 ComputeDirectIrradiance).
float sun_average_cosine(float mu_s, float sun_angular_radius) {
  float alpha = sun_angular_radius;
  if (!(alpha > 0.0)) return max(mu_s, 0.0);
  if (mu_s < -alpha) return 0.0;
  if (mu_s > alpha) return mu_s;
  return (mu_s + alpha) * (mu_s + alpha) / (4.0 * alpha);
}

// Direct sunlight on a horizontal surface, E T(r, mu_s) c(mu_s): added at
// run time because c bends within 2 alpha of the horizon, finer than the
// table's texels (docs/reference.md "Ground irradiance").
vec3 compute_direct_irradiance(AtmosphereParameters atm, sampler2D transmittance_lut, float r,
                               float mu_s) {
  float c = sun_average_cosine(mu_s, atm.sun_angular_radius);
  if (c == 0.0) return vec3(0.0);
  return atm.sun_illuminance * lookup_transmittance_to_top(transmittance_lut, atm, r, mu_s) * c;
}

// Bruneton 2017 GetSunAndSkyIrradiance for a surface at `point`
// (planet-centred, m) with unit `normal`: returns the sun's irradiance and
// sets sky_irradiance, the table's value scaled by the fraction of the sky
// the surface sees, (1 + dot(normal, up)) / 2.
vec3 sun_and_sky_irradiance(sampler2D irradiance_table, sampler2D transmittance_lut,
                            AtmosphereParameters atm, vec3 point, vec3 normal, vec3 sun_dir,
                            out vec3 sky_irradiance) {
  float r = length(point);
  vec3 up = point / r;
  float mu_s = dot(up, sun_dir);
  sky_irradiance = lookup_irradiance(irradiance_table, atm, r, mu_s) * (1.0 + dot(normal, up)) * 0.5;
  return atm.sun_illuminance * lookup_sun_transmittance(transmittance_lut, atm, r, mu_s) *
         max(dot(normal, sun_dir), 0.0);
}

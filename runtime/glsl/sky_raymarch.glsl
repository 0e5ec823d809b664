// requires: atmosphere_common.glsl, transmittance.glsl, multiscattering.glsl, sky_view.glsl
// skybake runtime: the ray march of Hillaire 2020 (eq. 1-4 with the multiple
// scattering of eq. 11), for the views the sky-view LUT does not cover
// (sec. 7: from space, "we seamlessly switch to simple ray marching"),
// reading the transmittance and multiple-scattering LUTs. C++:
// src/atmosphere/sky_integrator.hpp (integrate_scattered_luminance);
// docs/reference.md "The sky's ray march".
//
// The medium is described here by its density profiles (docs/reference.md
// "Atmosphere model"), up to MEDIUM_MAX_COMPONENTS components of up to
// MEDIUM_MAX_LAYERS layers each (Earth: Rayleigh, Mie and the two layers of
// the ozone tent); the preset's values are in manifest.json.

const int MEDIUM_MAX_COMPONENTS = 4;
const int MEDIUM_MAX_LAYERS = 2;
const int PHASE_NONE = 0;  // absorbs only (ozone)
const int PHASE_RAYLEIGH = 1;
const int PHASE_CORNETTE_SHANKS = 2;
const int PHASE_HENYEY_GREENSTEIN = 3;

// density(h) = clamp(exp_term exp(exp_scale h) + linear_term h + constant_term, 0, 1),
// h the altitude in m in every layer (Bruneton 2017 DensityProfileLayer).
struct DensityLayer {
  float width;          // m; ignored for the last layer
  float exp_term;       // a
  float exp_scale;      // b, 1/m
  float linear_term;    // c, 1/m
  float constant_term;  // d
};

struct MediumComponent {
  vec3 scattering;  // sigma_s at density 1, 1/m
  vec3 absorption;  // sigma_a at density 1, 1/m
  int phase;        // PHASE_*
  float g;          // asymmetry of a Mie phase
  int layer_count;  // 0: absent
  DensityLayer layers[MEDIUM_MAX_LAYERS];
};

struct AtmosphereMedium {
  int component_count;
  MediumComponent components[MEDIUM_MAX_COMPONENTS];
};

// The profile's density at altitude h, in [0, 1] (medium.hpp density_at).
float density_at(MediumComponent c, float h) {
  float layer_bottom = 0.0;
  for (int i = 0; i < c.layer_count; ++i) {
    DensityLayer l = c.layers[i];
    if (i + 1 == c.layer_count || h < layer_bottom + l.width) {
      float e = l.exp_term == 0.0 ? 0.0 : l.exp_term * exp(l.exp_scale * h);
      return clamp(e + l.linear_term * h + l.constant_term, 0.0, 1.0);
    }
    layer_bottom += l.width;
  }
  return 0.0;
}

float component_phase(MediumComponent c, float nu) {
  if (c.phase == PHASE_RAYLEIGH) return rayleigh_phase(nu);
  if (c.phase == PHASE_CORNETTE_SHANKS) return cornette_shanks_phase(nu, c.g);
  if (c.phase == PHASE_HENYEY_GREENSTEIN) return henyey_greenstein_phase(nu, c.g);
  return 0.0;
}

// (1 - exp(-x)) / sigma_t of Hillaire 2016 eq. 17 (the energy-conserving
// segment), written for x = sigma_t d near 0 without the cancellation of 1 - exp.
vec3 segment_weight(vec3 sigma_t, float d) {
  vec3 w;
  for (int c = 0; c < 3; ++c) {
    float x = sigma_t[c] * d;
    float one_minus_e = x < 1e-3 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - exp(-x);
    w[c] = sigma_t[c] > 0.0 ? one_minus_e / sigma_t[c] : d;
  }
  return w;
}

// Luminance from `position` along view_dir over at most max_distance_m
// (clipped to the atmosphere and the ground), `steps` segments (uniform, or
// quadratic t_i = t (i / n)^2), the medium sampled at each segment's middle;
// with lit_ground, the ground where the ray ends adds albedo / pi E T_sun
// max(mu_s, 0). `transmittance` receives the path's transmittance;
// multiscattering_mapping is the multiple-scattering table's sun axis.
vec3 integrate_scattered_luminance(AtmosphereParameters atm, AtmosphereMedium medium,
                                   sampler2D transmittance_lut, sampler2D multiscattering_lut,
                                   MultiscatteringMapping multiscattering_mapping, vec3 position,
                                   vec3 view_dir, vec3 sun_dir, float max_distance_m, int steps,
                                   bool quadratic, bool lit_ground, out vec3 transmittance) {
  transmittance = vec3(1.0);
  vec3 luminance = vec3(0.0);
  AtmosphereSpan span = clip_ray_to_atmosphere(atm, position, view_dir);
  if (!span.hits_atmosphere) return luminance;
  float t_end = min(span.t_exit, max(max_distance_m, 0.0));
  float nu = clamp_cosine(dot(view_dir, sun_dir));
  int n = max(steps, 1);
  float a = span.t_enter;
  for (int i = 1; i <= n && t_end > span.t_enter; ++i) {
    float x = float(i) / float(n);
    if (quadratic) x *= x;
    float b = i == n ? t_end : span.t_enter + (t_end - span.t_enter) * x;
    float dt = b - a;
    vec3 p = position + (0.5 * (a + b)) * view_dir;
    a = b;
    if (!(dt > 0.0)) continue;
    float r = max(length(p), atm.bottom_radius);
    float h = r - atm.bottom_radius;
    vec3 sigma_s = vec3(0.0), sigma_t = vec3(0.0), sigma_s_phase = vec3(0.0);
    for (int k = 0; k < medium.component_count; ++k) {
      MediumComponent c = medium.components[k];
      float density = density_at(c, h);
      sigma_s += density * c.scattering;
      sigma_t += density * (c.scattering + c.absorption);
      sigma_s_phase += density * c.scattering * component_phase(c, nu);
    }
    if (sigma_t == vec3(0.0)) continue;
    float mu_s = clamp_cosine(dot(p, sun_dir) / r);
    vec3 source = lookup_sun_transmittance(transmittance_lut, atm, r, mu_s) * sigma_s_phase +
                  lookup_multiscattering(multiscattering_lut, multiscattering_mapping, atm, r, mu_s) *
                      sigma_s;  // eq. 11
    vec3 w = segment_weight(sigma_t, dt);
    luminance += transmittance * atm.sun_illuminance * source * w;
    transmittance *= exp(-sigma_t * dt);
  }
  if (lit_ground && span.exits_on_ground && t_end >= span.t_exit) {
    vec3 up = normalize(position + span.t_exit * view_dir);
    float mu_s = clamp_cosine(dot(up, sun_dir));
    if (mu_s > 0.0)
      luminance += transmittance * atm.sun_illuminance *
                   lookup_sun_transmittance(transmittance_lut, atm, atm.bottom_radius, mu_s) *
                   mu_s * atm.ground_albedo / kPi;
  }
  return luminance;
}

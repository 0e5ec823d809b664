// skybake runtime: what every atmosphere include shares. HLSL, Shader Model
// 5 style (Texture2D / SamplerState, SampleLevel); the same functions, names
// and parameter order as runtime/glsl/atmosphere_common.glsl, which the GL
// tests run against the C++ (src/atmosphere/, src/core/math.hpp).
// Concatenate the includes in the order of their `// requires:` lines
// (docs/runtime.md "Using the includes").
//
// Units: lengths in metres, radii from the planet's centre; radiance and
// irradiance in units of the sun's illuminance at the top of the atmosphere
// (docs/architecture.md "Units"). Notation as in docs/reference.md.

// What the decode functions need to know about the atmosphere (manifest.json
// and the files' metadata; docs/runtime.md).
struct AtmosphereParameters {
  float bottom_radius;       // Rb, m
  float top_radius;          // Rt, m
  float3 sun_illuminance;    // at the top of the atmosphere (1 in the tables' units)
  float sun_angular_radius;  // rad
  float3 ground_albedo;      // diffuse, for lit ground
  float3 rayleigh_scattering;  // sigma_s of the Rayleigh group at density 1, 1/m
  float3 mie_scattering;       // sigma_s of the Mie group at density 1, 1/m
  int mie_phase;               // MIE_PHASE_CORNETTE_SHANKS or MIE_PHASE_HENYEY_GREENSTEIN
  float mie_g;                 // asymmetry of the Mie phase
};

static const float kPi = 3.14159265358979323846;
static const int MIE_PHASE_CORNETTE_SHANKS = 0;
static const int MIE_PHASE_HENYEY_GREENSTEIN = 1;

// Bruneton 2017 ClampCosine, SafeSqrt (docs/reference.md "Pitfalls").
float clamp_cosine(float mu) { return clamp(mu, -1.0, 1.0); }
float safe_sqrt(float a) { return sqrt(max(a, 0.0)); }

// Texel centres (docs/architecture.md "Texel centres").
float texel_coord_from_unit(float x, int n) { return 0.5 / float(n) + x * (1.0 - 1.0 / float(n)); }
float unit_from_texel_coord(float u, int n) { return (u - 0.5 / float(n)) / (1.0 - 1.0 / float(n)); }

// ---- Inverse trigonometry to float precision --------------------------------
// The built-in acos, asin and atan are approximations whose error the GLSL
// specification leaves open: Mesa's (llvmpipe) err by up to 1.6e-4 rad for
// acos and 3e-6 rad for atan (docs/runtime.md "Precision"), enough to move a
// sky-view read by a tenth of a texel. These are the single-precision
// minimax polynomials of the Cephes library (asinf, atanf; about 1e-7
// relative), on the usual range reductions.

// atan(x) for x >= 0: reduced below tan(pi/8) with atan(x) = pi/4 + atan((x - 1) / (x + 1))
// and atan(x) = pi/2 - atan(1 / x).
float atan_nonnegative(float x) {
  float y0 = 0.0;
  if (x > 2.414213562373095) {
    y0 = 0.5 * kPi;
    x = -1.0 / x;
  } else if (x > 0.4142135623730950) {
    y0 = 0.25 * kPi;
    x = (x - 1.0) / (x + 1.0);
  }
  float z = x * x;
  return y0 + (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z -
               3.33329491539e-1) * z * x + x;
}

float accurate_atan(float x) { return sign(x) * atan_nonnegative(abs(x)); }

// atan2 (GLSL's atan(y, x)): the angle of (x, y) in (-pi, pi]; 0 for (0, 0).
float accurate_atan2(float y, float x) {
  float ax = abs(x), ay = abs(y);
  if (ax == 0.0 && ay == 0.0) return 0.0;
  float a = ay <= ax ? atan_nonnegative(ay / ax) : 0.5 * kPi - atan_nonnegative(ax / ay);
  if (x < 0.0) a = kPi - a;
  return y < 0.0 ? -a : a;
}

// asin on [-1, 1]; above 0.5, asin(a) = pi/2 - 2 asin(sqrt((1 - a) / 2)).
float accurate_asin(float x) {
  float a = min(abs(x), 1.0);
  bool reduced = a > 0.5;
  float z = reduced ? 0.5 * (1.0 - a) : a * a;
  float t = reduced ? sqrt(z) : a;
  float y = ((((4.2163199048e-2 * z + 2.4181311049e-2) * z + 4.5470025998e-2) * z +
              7.4953002686e-2) * z + 1.6666752422e-1) * z * t + t;
  if (reduced) y = 0.5 * kPi - 2.0 * y;
  return x < 0.0 ? -y : y;
}

// acos on [-1, 1], accurate near +-1 too (through asin of the half-angle).
float accurate_acos(float x) {
  x = clamp_cosine(x);
  if (x < -0.5) return kPi - 2.0 * accurate_asin(sqrt(0.5 * (1.0 + x)));
  if (x > 0.5) return 2.0 * accurate_asin(sqrt(0.5 * (1.0 - x)));
  return 0.5 * kPi - accurate_asin(x);
}

// 1 - cos(a) without the cancellation of 1 - cos(a) near a = 0 (the sun's
// solid angle): 2 sin^2(a / 2).
float one_minus_cos(float a) {
  float s = sin(0.5 * a);
  return 2.0 * s * s;
}

// sqrt(Rt^2 - Rb^2).
float horizon_distance(AtmosphereParameters atm) {
  return sqrt((atm.top_radius - atm.bottom_radius) * (atm.top_radius + atm.bottom_radius));
}

// ---- Ray / sphere distances (src/atmosphere/geometry.hpp), written for
// float32 as in the GLSL: (R - r)(R + r) + (r mu)^2, and the product form
// of the root that would cancel.

float distance_to_top_boundary(float top, float r, float mu) {
  float c = (top - r) * (top + r);
  float q = safe_sqrt(c + (r * mu) * (r * mu));
  float d = mu > 0.0 ? c / max(r * mu + q, 1e-30) : q - r * mu;
  return max(d, 0.0);
}

float distance_to_bottom_boundary(float bottom, float r, float mu) {
  float c = (r - bottom) * (r + bottom);
  float q = safe_sqrt((r * mu) * (r * mu) - c);
  return max(c / max(q - r * mu, 1e-30), 0.0);
}

bool ray_intersects_ground(float bottom, float r, float mu) {
  return mu < 0.0 && (r * mu) * (r * mu) - (r - bottom) * (r + bottom) >= 0.0;
}

float radius_after(float r, float mu, float d) { return safe_sqrt(d * d + 2.0 * r * mu * d + r * r); }
float mu_after(float r, float mu, float d, float r_d) {
  return r_d > 0.0 ? clamp_cosine((r * mu + d) / r_d) : 1.0;
}

// ---- Phase functions (src/atmosphere/phase.hpp); cos_theta = nu.

float isotropic_phase() { return 1.0 / (4.0 * kPi); }

float rayleigh_phase(float cos_theta) {
  float c = clamp_cosine(cos_theta);
  return 3.0 * (1.0 + c * c) / (16.0 * kPi);
}

float cornette_shanks_phase(float cos_theta, float g) {
  float c = clamp_cosine(cos_theta);
  float k = 3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g);
  float w = 1.0 + g * g - 2.0 * g * c;
  return k * (1.0 + c * c) / (w * sqrt(w));
}

float henyey_greenstein_phase(float cos_theta, float g) {
  float c = clamp_cosine(cos_theta);
  float w = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * kPi * w * sqrt(w));
}

float mie_phase(AtmosphereParameters atm, float nu) {
  return atm.mie_phase == MIE_PHASE_HENYEY_GREENSTEIN ? henyey_greenstein_phase(nu, atm.mie_g)
                                                      : cornette_shanks_phase(nu, atm.mie_g);
}

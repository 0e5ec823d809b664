// The sky's ray march: in-scattered luminance and transmittance along a view
// ray through the atmosphere, shared by the sky-view and aerial-perspective
// bakers and by the preview renderer.
//
// Hillaire 2020 eq. 1-4 with the multiple-scattering term of eq. 11:
//   L = sum over segments of T(c, x) (1 - exp(-sigma_t dt)) / sigma_t
//       * E (Vis T_sun sum_i sigma_s,i p_i(nu) + Psi_ms sigma_s)
// where each medium component i scatters with its own phase function, T_sun
// comes from the transmittance LUT, Vis is the planet's shadow (0 when the
// sun ray from the sample meets the ground) and Psi_ms from the
// multiple-scattering LUT (section 5.5; omitted when no LUT is given).
// Segments are integrated in closed form with constant medium (Hillaire 2015;
// Hillaire 2016 eq. 17): the integral of S exp(-sigma_t t) over [0, dt] is
// S (1 - exp(-sigma_t dt)) / sigma_t, which never exceeds S / sigma_t however
// stiff the medium is; the medium of a segment is sampled at its midpoint.
//
// Frames and signs: positions are planet-centred in metres; view_dir is the
// direction the view ray travels from the viewer (away from the eye) and
// sun_dir points toward the sun. The scattering cosine is
// nu = dot(view_dir, sun_dir): light travels along -sun_dir and reaches the
// eye travelling along -view_dir, and the cosine between those two travel
// directions is dot(sun_dir, view_dir). Looking at the sun gives nu = 1, the
// forward peak of Mie (docs/reference.md "Atmosphere model"; phase.hpp uses
// the same convention).
//
// A viewer above the atmosphere is first moved to where the ray enters it
// (Hillaire's demo, MoveToTopAtmosphere); a viewer a rounding error below the
// ground is treated as standing on it.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/cached_finite_check.hpp"
#include "core/texture.hpp"
#include "core/texture_sampling.hpp"

namespace skybake {

struct MultiscatteringMapping;  // multiscattering_lut.hpp

// Where segment boundaries fall on a ray of length t_max cut into n segments.
//   uniform:   t_i = t_max i / n
//   quadratic: t_i = t_max (i / n)^2, short segments near the viewer where a
//              ground viewer's horizon rays cross the densest air, long ones
//              far away where the ray has climbed into thin air (Hillaire's
//              demo, VariableSampleCount).
enum class StepDistribution { uniform, quadratic };

struct IntegrationOptions {
  StepDistribution distribution = StepDistribution::uniform;
  // When the ray ends on the ground, add the ground's diffuse response
  // (eq. 1 L_o): albedo / pi * E * T_sun * max(mu_s, 0), attenuated by T.
  bool lit_ground = false;
  // Also end a segment where the ray enters or leaves the planet's shadow
  // (the cylinder of radius Rb behind the planet, where Vis of eq. 4 drops
  // to 0), so that no segment straddles the jump: the march then converges
  // as h^2 on every ray, where a straddled jump costs h (the error records'
  // references, pipeline/atmosphere_errors.cpp). The tables do not cut.
  bool cut_at_shadow = false;
  // Take the segments' density exponentials and their weights' expm1s in
  // blocks (core/kernels/exp_block.hpp: over lanes, within 1e-15
  // relative of libm) instead of one libm call each: the same march to
  // rounding (the error records' references, pipeline/atmosphere_errors.cpp;
  // the tables and the preview keep libm's bits).
  bool block_exponentials = false;
  // Read the sun's transmittance and Psi_ms at each segment's two ends and
  // integrate each channel's source linear between them against the
  // segment's exponential weight (segment_sources.hpp), instead of constant
  // at the midpoint; the medium stays sampled at the midpoint. In optically
  // thick segments the light comes from near the segment's start, where a
  // midpoint read is far off (the aerial record's reference,
  // pipeline/atmosphere_errors.cpp; docs/decisions/error-records.md). n + 1 reads of each table for n
  // segments. Takes the block path (block_exponentials).
  bool sources_at_ends = false;
  // Where set (null: none), the block march leaves out the reads whose
  // light is multiplied by 0, every segment after the transmittance from the
  // viewer has underflowed to 0 in all channels and a whole ray along which
  // no segment scatters (sigma_s = 0), once it has found both tables free of
  // NaN and infinity: each such term adds 0 times a finite source, so the
  // result has the same bits as with the reads (tests/atmosphere/
  // sky_integrator_test.cpp).
  const CachedFiniteCheck* finite_tables = nullptr;
  // The multiple-scattering table's mapping (multiscattering_mapping_of),
  // parsed once by a caller that marches many rays; null: parsed per ray.
  const MultiscatteringMapping* multiscattering_mapping = nullptr;
};

struct ScatteringResult {
  glm::dvec3 luminance{0.0};      // in-scattered luminance reaching the viewer, units of E
  glm::dvec3 transmittance{1.0};  // from the viewer to the end of the integrated path
};

// The part of a ray inside the atmosphere. Distances are from the ray origin.
struct AtmosphereSpan {
  bool hits_atmosphere = false;  // false: the ray misses the shell entirely
  double t_enter = 0.0;          // 0 unless the origin is above the top
  double t_exit = 0.0;           // where the ray meets the ground or leaves the top
  bool exits_on_ground = false;
};

// Clips the ray position + t dir (dir unit length) to the atmosphere shell.
AtmosphereSpan clip_ray_to_atmosphere(const Atmosphere& atm, glm::dvec3 position_m, glm::dvec3 dir);

// Integrates eq. 1-4 (+ eq. 11) from the viewer along view_dir over at most
// max_distance_m (clipped to the atmosphere and the ground) with `steps`
// segments. multiscattering_lut may be null (single scattering only).
// Directions must be unit length. Pure; thread-safe.
ScatteringResult integrate_scattered_luminance(const Atmosphere& atm,
                                               const Texture& transmittance_lut,
                                               const Texture* multiscattering_lut,
                                               glm::dvec3 position_m, glm::dvec3 view_dir,
                                               glm::dvec3 sun_dir, double max_distance_m, int steps,
                                               const IntegrationOptions& options = {});

// integrate_scattered_luminance's luminance extrapolated to zero step length
// (Richardson): (4 L(2n) - L(n)) / 3 with L(k) the march of k segments, both
// cut at the planet's shadow (options.cut_at_shadow is forced on), so every
// segment's integrand is smooth but for the input tables' bilinear kinks and
// the march's h^2 error cancels to leading order. The error records'
// reference (pipeline/atmosphere_errors.cpp): 3n segments where the plain
// march needed 300 for a several times larger error
// (docs/decisions/error-records.md).
glm::dvec3 extrapolated_scattered_luminance(const Atmosphere& atm, const Texture& transmittance_lut,
                                            const Texture* multiscattering_lut,
                                            glm::dvec3 position_m, glm::dvec3 view_dir,
                                            glm::dvec3 sun_dir, double max_distance_m, int n,
                                            IntegrationOptions options = {});

// The same march, cumulative: element k is the luminance and transmittance
// from the viewer to distance distances_m[k] (ascending, metres), each
// interval [d_(k-1), d_k] cut into steps_per_interval uniform segments. Paths
// that end at the ground or leave the atmosphere before d_k stop there, so
// the results are monotonic in k by construction. No lit ground.
std::vector<ScatteringResult> integrate_scattered_luminance_profile(
    const Atmosphere& atm, const Texture& transmittance_lut, const Texture* multiscattering_lut,
    glm::dvec3 position_m, glm::dvec3 view_dir, glm::dvec3 sun_dir,
    const std::vector<double>& distances_m, int steps_per_interval);

// One segment of constant extinction sigma_t and length d, per channel:
//   weight = (1 - exp(-sigma_t d)) / sigma_t  (d where sigma_t = 0), the
//            closed-form integral of exp(-sigma_t t) over [0, d];
//   transmittance = exp(-sigma_t d).
// One expm1 per channel gives both, exact for small sigma_t d.
struct SegmentWeights {
  glm::dvec3 weight;
  glm::dvec3 transmittance;
};
// Those weights from em[c] = expm1(-sigma_t[c] length_m), for callers that take
// the expm1s in blocks (sky_integrator.cpp's references).
inline SegmentWeights segment_weights_from_expm1(glm::dvec3 sigma_t, double length_m,
                                                 const double em[3]) {
  SegmentWeights w;
  for (int c = 0; c < 3; ++c) {
    w.weight[c] = sigma_t[c] > 0.0 ? -em[c] / sigma_t[c] : length_m;
    w.transmittance[c] = 1.0 + em[c];
  }
  return w;
}

inline SegmentWeights segment_weights(glm::dvec3 sigma_t, double length_m) {
  double em[3];
  for (int c = 0; c < 3; ++c) em[c] = std::expm1(-sigma_t[c] * length_m);  // exp(-x) - 1
  return segment_weights_from_expm1(sigma_t, length_m, em);
}

// Closed-form integral of a constant source S through constant extinction
// sigma_t over a segment: S (1 - exp(-sigma_t d)) / sigma_t per channel, and
// S d where sigma_t = 0.
inline glm::dvec3 integrate_segment(glm::dvec3 source, glm::dvec3 sigma_t, double length_m) {
  return source * segment_weights(sigma_t, length_m).weight;
}

// Transmittance from radius r toward a sun of zenith cosine mu_s, times the
// planet's shadow Vis of eq. 4: 0 when that ray meets the ground.
glm::dvec3 lookup_sun_transmittance(const Texture& transmittance_lut, const Atmosphere& atm,
                                    double r, double mu_s);

// lookup_sun_transmittance at the radius `at` was made for, bit for bit.
inline glm::dvec3 lookup_sun_transmittance(const Texture& transmittance_lut,
                                           const TransmittanceAtRadius& at, double bottom_m,
                                           double mu_s) {
  mu_s = clamp_cosine(mu_s);
  if (ray_intersects_ground(bottom_m, at.r, mu_s)) return glm::dvec3(0.0);  // Vis = 0
  return lookup_transmittance_to_top(transmittance_lut, at, mu_s);
}

}  // namespace skybake

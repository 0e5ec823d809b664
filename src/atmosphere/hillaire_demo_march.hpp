// Hillaire's public demo run-time march (UnrealEngineSkyAtmosphere,
// Hillaire 2020), written out from its formulas: his reads of the
// transmittance and multiscattering tables (in the "hillaire_demo"
// convention, table_convention.hpp) and his IntegrateScatteredLuminance.
// The bake of a Psi_ms fitted to his march (hillaire_demo_march_fit.hpp)
// and the report's section "Hillaire's runtime with skybake's tables"
// (report/hillaire_runtime.hpp) run it.
//
// The march: a view ray clipped to the atmosphere and the ground; with a
// variable sample count, n = lerp(min, max, clamp(t_max / 100 km)) samples
// on a squared distribution, each segment [t0, t1] sampled at
// t0 + 0.3 (t1 - t0); with a fixed count n, sample s at t_max (s + 0.3) / n,
// the segment the step from the previous sample ("far-end samples": the
// first step is 0.3 long and the last 0.7 of the ray is dropped). Per
// sample: the medium at the sample, the sun's transmittance and Psi_ms read
// from the tables, the planet's shadow by a ray toward the sun from 10 m
// above the sample, and the segment integrated in closed form
// (S - S T) / sigma_t. Psi_ms enters as Psi_ms sigma_s (eq. 11).
//
// The medium is skybake's (medium.hpp): per component sigma_s times its own
// phase, the same sum his Rayleigh + Cornette-Shanks Mie terms give for Earth.
// Lengths in metres; his constants given in km are converted.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "core/texture.hpp"

namespace skybake {

// Tables in his layout (the "hillaire_demo" convention).
struct DemoTables {
  const Texture* transmittance = nullptr;
  const Texture* multiscattering = nullptr;  // null: no multiple scattering
};

struct DemoMarch {
  bool variable = true;         // his VariableSampleCount
  double min_samples = 4.0;     // RayMarchMinMaxSPP (variable), or the fixed count in min_samples
  double max_samples = 14.0;
  bool mie_ray_phase = true;    // the components' phases; false: isotropic
  bool lit_ground = false;      // his `ground`: the lit ground's albedo / pi at a ground hit
  double segment_t = 0.3;       // where in its segment a sample sits (his SampleSegmentT)
  double max_distance = HUGE_VAL;  // his tMaxMax: the march stops there (a froxel's depth)
};

struct DemoMarchResult {
  glm::dvec3 luminance{0.0};     // units of the sun's illuminance
  glm::dvec3 transmittance{1.0};
  glm::dvec3 optical_depth{0.0};
  glm::dvec3 multi_scat_as_1{0.0};  // his MultiScatAs1: f_ms's integrand along the ray
};

// His reads (LutTransmittanceParamsToUv, GetMultipleScattering), bilinear, clamp.
glm::dvec3 demo_read_transmittance(const Atmosphere& atm, const Texture& lut, double r, double mu);
glm::dvec3 demo_read_multiscattering(const Atmosphere& atm, const Texture& lut, double r,
                                     double mu_s);

// His IntegrateScatteredLuminance from `position` (planet-centred; a viewer
// above the top first moved to it, his MoveToTopAtmosphere) along unit `dir`.
DemoMarchResult demo_integrate(const Atmosphere& atm, const DemoTables& tables,
                               glm::dvec3 position, glm::dvec3 dir, glm::dvec3 sun_dir,
                               const DemoMarch& march);

// His raySphereIntersectNearest: the nearest non-negative distance from
// `origin` along unit `dir` to the sphere, -1 when there is none.
double demo_sphere_nearest(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 centre, double radius);

// fromUnitToSubUvs and fromSubUvsToUnit of an n-texel axis.
double demo_to_sub_uv(double x, double n);
double demo_from_sub_uv(double u, double n);

}  // namespace skybake

// The path tracer's irradiance around a viewer, the reference of
// sky_irradiance (atmosphere/sky_irradiance.hpp) in its tests and in the
// report: radiance of every order (path_tracer.hpp) along the rays of a fine
// symmetric Gauss rule split at the viewer's horizon (sphere_rule.hpp),
// summed into
//   E(n) = int L(w) max(n . w, 0) dw           for each test normal,
//   L_k  = int L(w) Y_k(w) dw                  the L2 projection,
// so that the projection's own E (sh_l2_irradiance) is the best a 9-term
// fit can do: L2's limit (Ramamoorthi & Hanrahan 2001).
// With the sun below the horizon the paths gather the sun by the segment
// estimate (path_tracer.hpp), which converges in twilight.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/sky_irradiance.hpp"

namespace skybake {

struct IrradianceReference {
  std::vector<glm::dvec3> normals;
  std::vector<glm::dvec3> irradiance;  // E(n) per normal
  ShRadiance projection;               // the reference's own L2 coefficients
};

// n unit normals of a spherical Fibonacci set over the whole sphere.
std::vector<glm::dvec3> fibonacci_normals(int n);

struct IrradianceReferenceRule {
  int below = 8, above = 16, azimuths = 24;  // symmetric_gauss_rule
  int samples = 64;                          // paths per ray and channel
  int max_bounces = 64;
};

// At `altitude_m` under a sun of zenith angle sun_zenith_rad in the x-z
// plane, `normals` Fibonacci normals. Deterministic (fixed seeds);
// each ray's paths in parallel.
IrradianceReference reference_sky_irradiance(const Atmosphere& atm, double altitude_m,
                                             double sun_zenith_rad,
                                             const IrradianceReferenceRule& rule, int normals);

// Errors of E against the reference over the normals and channels, each
// relative to the mean of the reference E over the normals (per channel):
// RMS and max. A normal facing away from a low sun receives a small part of
// the light, and an error on it is judged against the light around.
struct IrradianceErrors {
  double rms = 0.0, max = 0.0;
};
IrradianceErrors irradiance_errors(const IrradianceReference& ref,
                                   const std::function<glm::dvec3(glm::dvec3)>& decode);

}  // namespace skybake

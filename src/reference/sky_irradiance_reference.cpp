#include "reference/sky_irradiance_reference.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/sh_l2.hpp"
#include "atmosphere/sphere_rule.hpp"
#include "reference/path_tracer.hpp"

namespace skybake {

std::vector<glm::dvec3> fibonacci_normals(int n) {
  std::vector<glm::dvec3> out;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double s = std::sqrt(std::max(1.0 - z * z, 0.0));
    out.push_back({s * std::cos(golden * i), s * std::sin(golden * i), z});
  }
  return out;
}

IrradianceReference reference_sky_irradiance(const Atmosphere& atm, double altitude_m,
                                             double sun_zenith_rad,
                                             const IrradianceReferenceRule& rule, int normals) {
  const double r = atm.bottom_radius_m + altitude_m;
  const double rb = atm.bottom_radius_m;
  const double mu_h = -std::sqrt(std::max((r - rb) * (r + rb), 0.0)) / r;
  const SphereRule dirs = symmetric_gauss_rule(rule.below, rule.above, rule.azimuths, mu_h);
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.samples = rule.samples;
  spec.max_bounces = rule.max_bounces;
  // Daylight keeps the collision estimate its figures were measured with;
  // with the sun below the horizon only the segment estimate converges
  // (path_tracer.hpp). Both are unbiased.
  if (sun_zenith_rad > 0.5 * kPi) spec.sun_estimate = SunEstimate::segment;
  const glm::dvec3 position(0.0, 0.0, r);
  const glm::dvec3 sun(std::sin(sun_zenith_rad), 0.0, std::cos(sun_zenith_rad));
  IrradianceReference ref;
  ref.normals = fibonacci_normals(normals);
  ref.irradiance.assign(ref.normals.size(), glm::dvec3(0.0));
  ref.projection.fill(glm::dvec3(0.0));
  for (size_t k = 0; k < dirs.dirs.size(); ++k) {
    spec.seed = 1000 + k;
    const glm::dvec3 d = dirs.dirs[k];
    const glm::dvec3 mirror(d.x, -d.y, d.z);
    const glm::dvec3 l = tracer.trace(position, d, sun, spec).mean;
    const double w = 4.0 * kPi * dirs.weights[k];
    // The rule's weight stands for d and its mirror image: half each.
    for (const glm::dvec3& e : {d, mirror}) {
      const std::array<double, kShL2Count> y = sh_l2_basis(e);
      for (int j = 0; j < kShL2Count; ++j) ref.projection[j] += 0.5 * w * y[j] * l;
      for (size_t i = 0; i < ref.normals.size(); ++i)
        ref.irradiance[i] += 0.5 * w * std::max(glm::dot(ref.normals[i], e), 0.0) * l;
    }
  }
  return ref;
}

IrradianceErrors irradiance_errors(const IrradianceReference& ref,
                                   const std::function<glm::dvec3(glm::dvec3)>& decode) {
  IrradianceErrors e;
  int n = 0;
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& v : ref.irradiance) mean += v / double(ref.irradiance.size());
  for (size_t i = 0; i < ref.normals.size(); ++i) {
    const glm::dvec3 got = decode(ref.normals[i]);
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(got[c] - ref.irradiance[i][c]) / mean[c];
      e.rms += rel * rel;
      e.max = std::max(e.max, rel);
      ++n;
    }
  }
  e.rms = std::sqrt(e.rms / n);
  return e;
}

}  // namespace skybake

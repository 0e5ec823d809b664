// The views and the models of the converged Psi_ms targets
// (converged_targets_test.cpp, converged_targets_accuracy_test.cpp): the
// path tracer over views like the report's, and the sky's ray march with
// Hillaire's table and the converged table's two estimators against it.
#pragma once

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "reference/path_tracer.hpp"
#include "report/sky_radiance.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake::converged_targets {

struct Views {
  glm::dvec3 position{0.0};
  std::vector<glm::dvec3> dirs, suns;
  std::vector<RadianceEstimate> traced;
};

// azimuths views per elevation, at phi = 2 pi (k + offset) / azimuths.
inline Views trace_views(const Atmosphere& atm, double altitude, int samples, int azimuths = 4,
                  double offset = 0.5) {
  Views v;
  v.position = glm::dvec3(0.0, 0.0, atm.bottom_radius_m + altitude);
  const double deg = kPi / 180.0;
  for (double sun : {60.0, 20.0, 5.0})
    for (double elevation : {5.0, 20.0, 60.0})
      for (int k = 0; k < azimuths; ++k) {
        const double e = elevation * deg, phi = 2.0 * kPi * (k + offset) / azimuths;
        v.dirs.push_back({std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e)});
        v.suns.push_back({std::cos(sun * deg), 0.0, std::sin(sun * deg)});
      }
  PathTracerSpec paths;
  paths.samples = samples;
  paths.max_bounces = 64;
  const SkyPathTracer tracer(atm);
  for (size_t i = 0; i < v.dirs.size(); ++i) {
    paths.seed = i + 1;
    v.traced.push_back(tracer.trace(v.position, v.dirs[i], v.suns[i], paths));
  }
  return v;
}

// Worst channel, denoised relative RMSE of the march with `table` against the tracer.
inline double sky_error(const Atmosphere& atm, const Texture& transmittance, const Texture& table,
                 const Views& v) {
  std::vector<RadiancePair> pairs;
  for (size_t i = 0; i < v.dirs.size(); ++i) {
    const glm::dvec3 l =
        integrate_scattered_luminance(atm, transmittance, &table, v.position, v.dirs[i],
                                      v.suns[i], 1e9, 96, {StepDistribution::quadratic})
            .luminance;
    pairs.push_back({l, v.traced[i].mean, v.traced[i].ci95, v.traced[i].mean});
  }
  return radiance_stats(pairs)["worst"]["rel_rmse_denoised"].get<double>();
}

struct ModelErrors {
  double hillaire = 0.0, mean = 0.0, relative = 0.0;
  double view = 0.0;  // relative, with the source by view (8 nu x 8 zenith slices)
};

inline ModelErrors model_errors(const Atmosphere& atm, const Views& views, bool small_iteration) {
  const Texture t = bake_transmittance_lut(atm, {128, 64, 64}, {});
  MultiscatteringLutSpec table{32, 32, 64, 20};
  ModelErrors e;
  e.hillaire = sky_error(atm, t, bake_multiscattering_lut(atm, t, table, {}), views);
  ConvergedMultiscatteringSpec spec;  // the option's defaults, or a small quick iteration
  if (small_iteration) {
    spec.bruneton.r_size = 8;
    spec.bruneton.mu_size = 32;
    spec.bruneton.mu_s_size = 8;
    spec.bruneton.nu_size = 8;
    spec.bruneton.tolerance = 1e-2;
  }
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  spec.estimator = PsiEstimator::mean;
  e.mean = sky_error(atm, t, converged_multiscattering_table(atm, t, table, spec, field, {}), views);
  spec.estimator = PsiEstimator::relative;
  e.relative =
      sky_error(atm, t, converged_multiscattering_table(atm, t, table, spec, field, {}), views);
  spec.nu_slices = spec.zenith_slices = 8;
  e.view = sky_error(atm, t, converged_multiscattering_table(atm, t, table, spec, field, {}), views);
  return e;
}

// Earth over the report's own 72 views (8 azimuths from the sun's, camera at
// 200 m), `paths` paths a view: the relative estimator within 2 %, worst
// channel, and at most half of Hillaire's table's error.
inline void expect_earth_within_two_percent(int paths) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const ModelErrors e = model_errors(atm, trace_views(atm, 200.0, paths, 8, 0.0), false);
  EXPECT_LT(e.relative, 0.02) << "mean " << e.mean << ", Hillaire " << e.hillaire;
  EXPECT_LT(e.relative, 0.5 * e.hillaire) << "Hillaire " << e.hillaire;
}

// presets/mars.json shrunk k = 339 times (radius 10 km): heights / k,
// coefficients x k, so every optical depth and the ratio of scale height to
// radius stay Mars' (dust of g = 0.85, optical depth 0.17, over Rayleigh
// stronger in red); the camera at 200 m / k.
constexpr double kMarsScale = 339.0;
inline Atmosphere small_mars() {
  const double k = kMarsScale;
  Atmosphere atm;
  atm.bottom_radius_m = 3386.19e3 / k;
  atm.top_radius_m = 3463.17e3 / k;
  atm.ground_albedo = glm::dvec3(0.35, 0.22, 0.13);
  atm.components = {
      fixtures::make_component("rayleigh", glm::dvec3(19.918e-6, 13.57e-6, 5.75e-6) * k,
                               glm::dvec3(0.0), exponential_profile(10.44e3 / k),
                               PhaseKind::rayleigh),
      fixtures::make_component("mie", glm::dvec3(53.618e-6) * k, glm::dvec3(0.55309e-6) * k,
                               exponential_profile(3.095e3 / k), PhaseKind::cornette_shanks,
                               0.85)};
  return atm;
}

// Mars shrunk (small_mars, above) over the report's 72 views, `paths` paths
// a view: the source by view within 8 %, worst channel, at most half the
// isotropic relative estimator's error and below Hillaire's table's.
inline void expect_mars_view_source_within_eight_percent(int paths) {
  const Atmosphere atm = small_mars();
  const ModelErrors e = model_errors(atm, trace_views(atm, 200.0 / kMarsScale, paths, 8, 0.0), false);
  EXPECT_LT(e.view, 0.08) << "relative " << e.relative << ", Hillaire " << e.hillaire;
  EXPECT_LT(e.view, 0.5 * e.relative) << "relative " << e.relative;
  EXPECT_LT(e.view, e.hillaire) << "Hillaire " << e.hillaire;
}

}  // namespace skybake::converged_targets

// Sky radiance of `skybake report` (docs/report.md): what a viewer sees, rendered
// from the LUTs the way an engine renders it, against the Monte Carlo path
// tracer (reference/path_tracer.hpp), which solves the full radiative
// transfer: every scattering order, the ground's bounce with the scene's
// albedo, the planet's shadow.
//
// Views: a camera near the ground (200 m, at most half the atmosphere's
// thickness) looking at view_azimuths azimuths (from the sun's) x the level's
// elevations above the horizon, under each sun elevation of the level.
// LUT side: per sun elevation one sky-view layer is baked for the camera's
// altitude with the preset's sky-view settings, reading the operating-point
// transmittance and multiple-scattering tables, and read through
// render_sky_luminance (sky_render.hpp) without the sun disk (the path
// tracer's radiance has no sun disk either).
//
// Comparisons:
// - "multiple": the model an engine ships (single + Hillaire's Psi_ms) against
//   the path tracer with every order (max_bounces grows with the optical
//   depth, see the code) and the ground bounce;
// - "second_order_vs_path_tracer": the model with Psi_ms replaced by its
//   second order L_2 alone against the path tracer limited to two vertices:
//   whether a multiple-scattering error comes from L_2's assumptions
//   (isotropic phase, the same light everywhere) or from the series
//   1 / (1 - f_ms) standing for the orders >= 3;
// - "single": the sky-view layer baked with Psi_ms = 0 against the path tracer
//   limited to one vertex and a black ground, and against adaptive
//   quadrature (reference_single_scattering, noise free). Single scattering
//   separates the tables' own error from the multiple-scattering
//   approximation's; the quadrature also checks the path tracer.
// "multiple_scattering_share": the fraction of the path-traced radiance that
// orders >= 2 carry, per channel (1 - quadrature single / path traced).
//
// Statistics per channel over the views (X the path tracer's mean, se its
// standard error = ci95 / 1.96, L the LUT's value; every "/ X" below divides
// by max(X, 1e-3 x the view's all-orders radiance), so that a partial
// quantity too faint to see, such as single scattering under an optical
// depth of 26, cannot dominate):
//   rel_rmse          sqrt(mean(((L - X) / X)^2))        includes the reference noise
//   noise_rel_rms     sqrt(mean((se / X)^2))             the reference noise alone
//   rel_rmse_denoised sqrt(max(rel_rmse^2 - noise^2, 0)) E[(L - X)^2] = (L - E X)^2 + se^2
//   rel_bias          mean((L - X) / X)                  the sign of a systematic error
//   max_rel, rmse (absolute, units of the sun's illuminance), max_ci95_rel.
// Target (stated for Earth's daytime sky): relative RMSE < 1% for the model
// with multiple scattering, worst channel, over every sun elevation (all are
// above the horizon). "met" when even the noisy rel_rmse is below it, "not
// met" when the denoised one is above it, else "undetermined" (the reference
// is too noisy to tell; raise the path count).
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/texture.hpp"
#include "report/setup.hpp"

namespace skybake {

// The views and the path tracer's sample counts.
struct SkyRadianceSetup {
  std::vector<double> sun_elevations_deg;
  std::vector<double> view_elevations_deg;
  int view_azimuths = 8;
  int path_samples = 0;         // paths per channel and view, every order
  int path_samples_single = 0;  // the same for single scattering (also checked by quadrature)

  static SkyRadianceSetup quick();
  static SkyRadianceSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SkyRadianceSetup, sun_elevations_deg, view_elevations_deg,
                                   view_azimuths, path_samples, path_samples_single)

nlohmann::json sky_radiance_report(const ReportInputs& in, const SkyRadianceSetup& setup);

// The camera of the views above: its altitude and position (planet-centred,
// on the z axis), the view directions of one sun elevation in its local frame
// (z up, the sun at azimuth 0; elevations outer, azimuths inner) and the
// sky-view settings its layers are baked with (`views` set per sun).
struct SkyRadianceCamera {
  double altitude_m = 0.0;
  glm::dvec3 position{0.0};
  std::vector<glm::dvec3> dirs;
  SkyviewLutSpec sky;
};
SkyRadianceCamera sky_radiance_camera(const Scene& scene, const SkyRadianceSetup& setup);

// The sun of one sun elevation in the camera's frame.
glm::dvec3 sky_radiance_sun(double sun_elevation_deg);

// The LUT side of the views of one sun elevation, rendered from a
// multiple-scattering table as the report renders them: one sky-view layer
// baked for the camera from `transmittance` and `multiscattering`, read
// through render_sky_luminance without sun disk and ground. Linear in the
// table's texels (report/psi_weights.hpp).
std::vector<glm::dvec3> render_sky_views(const Atmosphere& atm, const Texture& transmittance,
                                         const Texture& multiscattering,
                                         const SkyRadianceCamera& camera,
                                         double sun_elevation_deg);

// Scattering orders the path tracer follows for the views' references.
int sky_radiance_max_bounces(const Atmosphere& atm);

// One view's values: the LUTs', and a reference with its 95% half-width (0
// for the quadrature). `scale` is the view's path-traced radiance with every
// order: relative errors divide by max(reference, 1e-3 scale) (above).
struct RadiancePair {
  glm::dvec3 lut{0.0}, mean{0.0}, ci95{0.0}, scale{0.0};
};

// The statistics above, per channel ("channels") and the worst channel ("worst").
nlohmann::json radiance_stats(const std::vector<RadiancePair>& rows);

constexpr double kDaytimeRelativeRmseTarget = 0.01;

// The nu slices of the converged model's view-dependent table the report
// renders beside the isotropic ones (docs/report.md "Two Psi_ms models").
constexpr int kReportNuSlices = 8;
constexpr int kReportZenithSlices = 8;

// The daytime target judged on radiance statistics (radiance_stats): "met"
// when even the noisy worst-channel rel_rmse is below it, "not met" when the
// denoised one is above it, else "undetermined".
nlohmann::json target_json(const nlohmann::json& stats);

}  // namespace skybake

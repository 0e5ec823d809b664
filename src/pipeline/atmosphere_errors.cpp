// The measured error of Hillaire's tables (error_measures.hpp): the queries
// of verify/query_points.hpp, read with each table's lookup_*, against
// the same quantity integrated at those points with many more steps and, for
// transmittance, no table at all. The sky tables' references read the same
// input tables the bake read (transmittance, multiple scattering), as the
// report's do, so each table's own error is measured.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <tbb/parallel_for.h>

#include <fmt/format.h>

#include "atmosphere/sky_integrator.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/error_measures.hpp"
#include "verify/error_references.hpp"
#include "verify/psi_ms_reference.hpp"
#include "verify/query_points.hpp"

namespace skybake {

nlohmann::json measure_transmittance_error(const Scene& scene, const OutputSpec&,
                                           const ProductInputs&, const Texture& lut) {
  const Atmosphere& atm = scene.atmosphere;
  QueryReads reads(kTransmittanceQueries);
  std::vector<glm::dvec2> rays(reads.size());
  for (size_t i = 0; i < reads.size(); ++i) {
    const RadiusCosine q = transmittance_query(atm, i);
    rays[i] = {q.r, q.mu};
    reads[i].first = lookup_transmittance_to_top(lut, atm, q.r, q.mu);
  }
  const std::vector<glm::dvec3> reference =
      compute_transmittances_to_top(atm, rays, kTransmittanceReferenceSteps,
                                    SegmentRule::gauss3, NodeExp::block);
  for (size_t i = 0; i < reads.size(); ++i) reads[i].second = reference[i];
  return error_record(
      reads,
      fmt::format("lookup_transmittance_to_top (bilinear) at points uniform in the table's "
                  "(x_mu, x_r) square against the optical depth integrated from scratch with {} "
                  "steps (compute_transmittance_to_top, no table)",
                  kTransmittanceReferenceSteps));
}

namespace {

// The converged model: the table's reads against the same mean taken at the
// query points themselves, over the same 4D iteration (recomputed: the bake
// keeps none of it), so the record is the table's interpolation error.
nlohmann::json measure_converged_multiscattering_error(const Scene& scene, const OutputSpec& spec,
                                                       const ProductInputs& in,
                                                       const Texture& lut) {
  const Atmosphere& atm = scene.atmosphere;
  const ConvergedMultiscatteringSpec c = converged_multiscattering_spec(spec);
  const ConvergedField field =
      compute_converged_field(atm, *in.at("transmittance"), c, BakeContext{});
  const PsiQuadrature quadrature = psi_quadrature(c, field.phases);
  const MultiscatteringMapping mapping = multiscattering_mapping_of(lut);
  QueryReads reads(kMultiscatteringQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const RadiusCosine q = multiscattering_query(atm, i);
    reads[i].first = lookup_multiscattering(lut, mapping, atm, q.r, q.mu);
    reads[i].second =
        compute_converged_multiscattering(atm, *in.at("transmittance"), field, q.r, q.mu,
                                          quadrature);
  });
  return error_record(
      reads, "lookup_multiscattering (bilinear) at points uniform in altitude and sun zenith "
             "cosine against the mean incident radiance at the points themselves over the same "
             "4D order iteration (compute_converged_multiscattering)");
}

}  // namespace

nlohmann::json measure_multiscattering_error(const Scene& scene, const OutputSpec& spec,
                                             const ProductInputs& in, const Texture& lut) {
  if (multiscattering_is_converged(spec))
    return measure_converged_multiscattering_error(scene, spec, in, lut);
  const Atmosphere& atm = scene.atmosphere;
  const PointRule rule = point_rule(kMultiscatteringReference);
  const Texture& transmittance = *in.at("transmittance");
  const CachedFiniteCheck finite{&transmittance};
  QueryReads reads(kMultiscatteringQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const RadiusCosine q = multiscattering_query(atm, i);
    reads[i].first = lookup_multiscattering(lut, atm, q.r, q.mu);
    reads[i].second =
        multiscattering_at_point(atm, transmittance, q.r, q.mu, rule, &finite).psi_ms;
  });
  return error_record(
      reads,
      fmt::format("lookup_multiscattering (bilinear) at points uniform in altitude and sun "
                  "zenith cosine against the same integral (Hillaire 2020 eq. 5-10) at the "
                  "points themselves: {} + {} zenith cosines split at the horizon, Gauss-Legendre "
                  "in s where mu = mu_h -+ c s^2, x {} azimuths ({} lit, each with its mirror "
                  "image across the sun's plane), {} segments per ray graded toward the densest "
                  "air (multiscattering_at_point), reading the same transmittance table",
                  kMultiscatteringReference.below, kMultiscatteringReference.above,
                  2 * kMultiscatteringReference.azimuths, kMultiscatteringReference.azimuths,
                  kMultiscatteringReference.steps));
}

namespace {

// The sky-view table read at the query points against the same single-
// scattering march finer, reading `multiscattering` (null: none), plus
// `more_light` toward each query's direction.
QueryReads skyview_reads(
    const Atmosphere& atm, const Texture& lut, const Texture& transmittance,
    const Texture* multiscattering, const SkyviewLutSpec& baked,
    const std::function<glm::dvec3(double r, const SkyviewDirection& view, double zenith)>&
        more_light) {
  IntegrationOptions options;
  options.distribution = baked.distribution;
  options.block_exponentials = true;
  const CachedFiniteCheck finite{&transmittance, multiscattering};
  options.finite_tables = &finite;
  const MultiscatteringMapping mapping =
      multiscattering ? multiscattering_mapping_of(*multiscattering) : MultiscatteringMapping{};
  options.multiscattering_mapping = &mapping;
  QueryReads reads(kSkyviewQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const SkyviewQueryPoint q = skyview_query(atm, baked.views, i);
    const double zenith = baked.views[size_t(q.layer)].sun_zenith_rad;
    const glm::dvec3 sun(std::sin(zenith), 0.0, std::cos(zenith));
    reads[i].first = lookup_skyview(lut, q.layer, atm, q.r, q.view);
    reads[i].second =
        extrapolated_scattered_luminance(atm, transmittance, multiscattering, {0.0, 0.0, q.r},
                                         skyview_vector_from_direction(q.view), sun, INFINITY,
                                         kSkyviewReferenceSteps, options) +
        more_light(q.r, q.view, zenith);
  });
  return reads;
}

// Sky-view with the 4D table's orders >= 2: the same single-scattering march
// finer plus the same iteration's orders >= 2 at the query's own direction
// (the iteration recomputed), so the record is the layer's interpolation
// and march error.
nlohmann::json measure_skyview_multiple4d_error(const Scene& scene, const OutputSpec& spec,
                                                const ProductInputs& in, const Texture& lut) {
  const Atmosphere& atm = scene.atmosphere;
  const ConvergedField field = compute_converged_field(
      atm, *in.at("transmittance"), skyview_multiple4d_spec(spec, atm), BakeContext{});
  const QueryReads reads = skyview_reads(
      atm, lut, *in.at("transmittance"), nullptr, skyview_spec(spec),
      [&](double r, const SkyviewDirection& view, double zenith) {
        return lookup_field_multiple_scattering(atm, field, r, view, zenith);
      });
  return error_record(
      reads, fmt::format("lookup_skyview (bilinear, azimuth wraps) at a uniform layer and view "
                         "direction against single scattering marched with {} and {} steps, cut at "
                         "the planet's shadow and extrapolated to zero step (Richardson), plus the "
                         "same 4D iteration's orders >= 2 toward that direction",
                         2 * kSkyviewReferenceSteps, kSkyviewReferenceSteps));
}

}  // namespace

nlohmann::json measure_skyview_error(const Scene& scene, const OutputSpec& spec,
                                     const ProductInputs& in, const Texture& lut) {
  if (skyview_uses_multiple4d(spec)) return measure_skyview_multiple4d_error(scene, spec, in, lut);
  const QueryReads reads =
      skyview_reads(scene.atmosphere, lut, *in.at("transmittance"), in.at("multiscattering"),
                    skyview_spec(spec),
                    [](double, const SkyviewDirection&, double) { return glm::dvec3(0.0); });
  return error_record(
      reads, fmt::format("lookup_skyview (bilinear, azimuth wraps) at a uniform layer and view "
                         "direction against the same march with {} and {} steps, cut at the "
                         "planet's shadow and extrapolated to zero step (Richardson), reading the "
                         "same transmittance and multiple-scattering tables",
                         2 * kSkyviewReferenceSteps, kSkyviewReferenceSteps));
}

nlohmann::json measure_aerial_perspective_error(const Scene& scene, const OutputSpec& spec,
                                                const ProductInputs& in, const Texture& lut) {
  const Atmosphere& atm = scene.atmosphere;
  const AerialPerspectiveSpec baked = aerial_perspective_spec(spec);
  const glm::dvec3 sun = sun_direction(baked.sun_zenith_rad, baked.sun_azimuth_rad);
  IntegrationOptions options = aerial_reference_options();
  const Texture* multiscattering = in.at("multiscattering");
  const CachedFiniteCheck finite{in.at("transmittance"), multiscattering};
  options.finite_tables = &finite;
  const MultiscatteringMapping mapping =
      multiscattering ? multiscattering_mapping_of(*multiscattering) : MultiscatteringMapping{};
  options.multiscattering_mapping = &mapping;
  QueryReads reads(kAerialQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const AerialQueryPoint q = aerial_query(atm, baked, i);
    reads[i].first =
        glm::dvec3(lookup_aerial_perspective(lut, baked.depth_range_m, q.screen_uv, q.distance_m));
    const int steps = aerial_reference_segments(q.distance_m, baked.depth_range_m);
    reads[i].second = integrate_scattered_luminance(atm, *in.at("transmittance"),
                                                    in.at("multiscattering"), q.position,
                                                    q.view_dir, sun, q.distance_m, steps, options)
                          .luminance;
  });
  return error_record(
      reads,
      fmt::format("lookup_aerial_perspective (trilinear, RGB) at a uniform screen position and "
                  "a distance uniform up to the nearer of the depth range and the ground, "
                  "against the same march from the camera in uniform steps, {} over the depth "
                  "range (at least {} a query), the sun's transmittance and Psi_ms read at each "
                  "step's ends and integrated linear across it against the step's exponential "
                  "weight, reading the same transmittance and multiple-scattering tables",
                  kAerialReferenceSteps, kAerialMinSteps));
}

}  // namespace skybake

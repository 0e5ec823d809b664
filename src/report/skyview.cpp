// Sky-view ladder of `skybake report` (ladders.hpp): steps x sizes
// over the preset's layers (viewer altitude, sun zenith), each table read
// with lookup_skyview at pseudo-random (layer, view direction) and compared
// two ways:
// - the full model (single + Hillaire's multiple scattering) against the same
//   march (sky_integrator.hpp) with many more steps, reading the same
//   transmittance and multiple-scattering tables: the sky-view table's own
//   error (march steps, resolution, interpolation); the primary numbers;
// - single scattering only (the table baked with a zero Psi_ms) against
//   adaptive quadrature (reference_single_scattering), which reads no table
//   at all: "single_scattering" in each point. This one also carries the
//   transmittance table's error (the sun's transmittance at every sample).
// The run time is that of the full bake.
//
// Queries: layer uniform, view direction uniform on the sphere (mu uniform in
// [-1, 1], azimuth uniform): below the horizon the table holds the
// in-scattering up to the ground, and engines read it there too.
#include <algorithm>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/skyview_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/skyview.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct SkyviewQuery {
  int layer = 0;
  double r = 0.0;
  SkyviewDirection view;
  glm::dvec3 reference{0.0};         // full model, fine march
  glm::dvec3 single_reference{0.0};  // single scattering, quadrature
};

glm::dvec3 layer_sun(const SkyviewView& v) {
  return {std::sin(v.sun_zenith_rad), 0.0, std::cos(v.sun_zenith_rad)};
}

std::vector<SkyviewQuery> skyview_queries(const ReportInputs& in, const SkyviewSetup& setup,
                                          const SkyviewLutSpec& op) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<SkyviewQuery> q(size_t(setup.skyview_queries));
  IntegrationOptions fine;
  fine.distribution = op.distribution;
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    SkyviewQuery& s = q[i];
    const SkyviewQueryPoint point = skyview_query(atm, op.views, i);
    s.layer = point.layer;
    s.r = point.r;
    s.view = point.view;
    const SkyviewView& v = op.views[size_t(s.layer)];
    const glm::dvec3 position(0.0, 0.0, s.r), dir = skyview_vector_from_direction(s.view);
    s.reference =
        integrate_scattered_luminance(atm, in.transmittance, &in.multiscattering, position, dir,
                                      layer_sun(v), INFINITY, setup.skyview_reference_steps, fine)
            .luminance;
    s.single_reference = reference_single_scattering(atm, position, dir, layer_sun(v),
                                                     in.level.single_scattering_tolerance)
                             .value;
  });
  return q;
}

ErrorStats measure(const Texture& lut, const Atmosphere& atm,
                   const std::vector<SkyviewQuery>& queries, bool single) {
  ErrorTally tally;
  for (const SkyviewQuery& q : queries) {
    const glm::dvec3 l = lookup_skyview(lut, q.layer, atm, q.r, q.view);
    const glm::dvec3& ref = single ? q.single_reference : q.reference;
    for (int c = 0; c < 3; ++c) tally.add(l[c], ref[c]);
  }
  return tally.stats();
}

}  // namespace

SkyviewSetup SkyviewSetup::full() {
  SkyviewSetup s;
  s.skyview_steps = {8, 15, 30, 60};
  s.skyview_sizes = {{96, 54}, {192, 108}, {384, 216}};
  s.skyview_queries = 1024;
  s.skyview_reference_steps = 2000;
  return s;
}

SkyviewSetup SkyviewSetup::quick() {
  SkyviewSetup s;
  s.skyview_steps = {8, 30};
  s.skyview_sizes = {{96, 54}, {192, 108}};
  s.skyview_queries = 128;
  s.skyview_reference_steps = 600;
  return s;
}

nlohmann::json skyview_report(const ReportInputs& in, const SkyviewSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const SkyviewLutSpec op = skyview_spec(operating_spec(in.scene, "skyview"));
  in.stage("skyview: reference march and quadrature");
  const std::vector<SkyviewQuery> queries = skyview_queries(in, setup, op);
  Texture no_multiscattering = in.multiscattering;
  std::fill(no_multiscattering.data.begin(), no_multiscattering.data.end(), 0.0f);

  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& size : setup.skyview_sizes)
    for (int steps : setup.skyview_steps) grid.push_back({{"size", size}, {"steps", steps}});
  const nlohmann::json axes = {{"steps", setup.skyview_steps}, {"size", setup.skyview_sizes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    SkyviewLutSpec spec = op;
    spec.width = s["size"][0];
    spec.height = s["size"][1];
    spec.steps = s["steps"];
    Texture lut;
    const double seconds = time_bake(
        [&] {
          return bake_skyview_lut(atm, in.transmittance, in.multiscattering, spec, BakeContext{});
        },
        lut, in.level.min_timing_seconds);
    nlohmann::json point = measure(lut, atm, queries, false).json();
    point["seconds"] = seconds;
    const Texture single =
        bake_skyview_lut(atm, in.transmittance, no_multiscattering, spec, BakeContext{});
    point["single_scattering"] = measure(single, atm, queries, true).json();
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.width, op.height}}, {"steps", op.steps}};
  nlohmann::json out = run_ladder("skyview", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "skyview";
  out["kind"] = "lut";
  out["layers"] = op.views.size();
  out["reference"] = fmt::format(
      "max_rel/rms_rel: the same march with {} steps reading the same transmittance and "
      "multiple-scattering tables; single_scattering: adaptive quadrature "
      "(reference_single_scattering, tolerance {:g}) against the table baked without Psi_ms",
      setup.skyview_reference_steps, in.level.single_scattering_tolerance);
  out["queries"] = fmt::format(
      "{} points: layer uniform over the preset's {} layers, view direction uniform on the "
      "sphere, 3 channels each; lookup_skyview (bilinear, azimuth wraps)",
      queries.size(), op.views.size());
  // The half round trip of the operating point's table (not kept by the
  // ladder: one more bake, the cost of one ladder point).
  const Texture lut =
      bake_skyview_lut(atm, in.transmittance, in.multiscattering, op, BakeContext{});
  out["half"] = {{"float", measure(lut, atm, queries, false).json()},
                 {"half", measure(half_round_trip(lut), atm, queries, false).json()},
                 {"storage", half_storage_stats(lut)}};
  return out;
}

}  // namespace skybake

// Scattering (Bruneton 4D) ladder of `skybake report` (ladders.hpp):
// table shapes x ray nodes, each baked with one order (single scattering,
// the part of the table an independent quadrature can check to 1e-6) in the
// preset's Mie storage, read with lookup_scattering at pseudo-random
// (r, mu, mu_s, nu) and compared with adaptive quadrature of single
// scattering (reference_single_scattering: no table at all, the planet's
// shadow included). This is the table's own error: parameterization,
// interpolation, ray quadrature, Mie-in-alpha. The orders >= 2 are measured
// against the path tracer in the bruneton_comparison section.
//
// Queries: altitude top * u^2 (denser near the ground, where the sky is
// seen from), mu uniform in [-1, 1], mu_s uniform in [mu_s_min, 1], the
// azimuth between view and sun uniform.
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/scattering.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct ScatteringQuery {
  double r = 0.0, mu = 0.0, mu_s = 0.0, nu = 0.0;
  bool hits_ground = false;
  glm::dvec3 reference{0.0};
};

std::vector<ScatteringQuery> scattering_queries(const ReportInputs& in, int count,
                                                double mu_s_min) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<ScatteringQuery> q(static_cast<size_t>(count));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const ViewQuery v = view_query(atm, i, kScatteringQueryDim, mu_s_min);
    q[i].r = v.r, q[i].mu = v.mu, q[i].mu_s = v.mu_s, q[i].nu = v.nu;
    q[i].hits_ground = v.hits_ground;
    q[i].reference = reference_single_scattering(atm, q[i].r, q[i].mu, q[i].mu_s, q[i].nu,
                                                 in.level.single_scattering_tolerance)
                         .value;
  });
  return q;
}

nlohmann::json measure(const Atmosphere& atm, const BrunetonTextures& t,
                       const std::vector<ScatteringQuery>& queries) {
  const Texture no_mie;
  const Texture& mie = t.scattering.channel_count() >= 4 ? no_mie : t.single_mie;
  ErrorTally tally;
  for (const ScatteringQuery& q : queries) {
    const glm::dvec3 v =
        lookup_scattering(t.scattering, mie, t.shape, atm, q.r, q.mu, q.mu_s, q.nu, q.hits_ground);
    for (int c = 0; c < 3; ++c) tally.add(v[c], q.reference[c]);
  }
  return tally.stats().json();
}

}  // namespace

ScatteringSetup ScatteringSetup::full() {
  ScatteringSetup s;
  s.scattering_shapes = {{8, 32, 8, 4}, {16, 64, 16, 8}, {32, 128, 32, 8}, {32, 256, 32, 16}};
  s.scattering_ray_nodes = {15, 30, 51, 99};
  s.scattering_queries = 1024;
  return s;
}

ScatteringSetup ScatteringSetup::quick() {
  ScatteringSetup s;
  s.scattering_shapes = {{8, 32, 8, 4}, {16, 64, 16, 8}};
  s.scattering_ray_nodes = {15, 51};
  s.scattering_queries = 64;
  return s;
}

nlohmann::json scattering_report(const ReportInputs& in, const ScatteringSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  BrunetonSpec op = bruneton_spec(operating_spec(in.scene, "scattering"));
  op.orders = 1;
  op.tolerance = 0.0;
  in.stage("scattering: reference quadrature");
  const std::vector<ScatteringQuery> queries =
      scattering_queries(in, setup.scattering_queries, op.mu_s_min);

  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& shape : setup.scattering_shapes)
    for (int nodes : setup.scattering_ray_nodes)
      grid.push_back({{"size", shape}, {"ray_nodes", nodes}});
  const nlohmann::json axes = {{"ray_nodes", setup.scattering_ray_nodes},
                               {"size", setup.scattering_shapes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    BrunetonSpec spec = op;
    spec.r_size = s["size"][0];
    spec.mu_size = s["size"][1];
    spec.mu_s_size = s["size"][2];
    spec.nu_size = s["size"][3];
    spec.ray_nodes = s["ray_nodes"];
    BrunetonTextures t;
    const double seconds =
        time_bake([&] { return bake_bruneton(atm, in.transmittance, spec, BakeContext{}); }, t,
                  in.level.min_timing_seconds);
    nlohmann::json point = measure(atm, t, queries);
    point["seconds"] = seconds;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.r_size, op.mu_size, op.mu_s_size, op.nu_size}},
                                      {"ray_nodes", op.ray_nodes}};
  nlohmann::json out = run_ladder("scattering", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "scattering";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "adaptive quadrature of single scattering (reference_single_scattering, tolerance {:g}), "
      "independent of every table; each point bakes one order (the table's own error: mapping, "
      "interpolation, ray quadrature, Mie storage '{}'); orders >= 2 are in "
      "bruneton_comparison, against the path tracer",
      in.level.single_scattering_tolerance, op.combined_mie_alpha ? "alpha" : "separate");
  out["queries"] = fmt::format(
      "{} points: altitude top*u^2, mu uniform, mu_s uniform in [mu_s_min, 1], azimuth "
      "uniform; lookup_scattering (quadrilinear, nu slices lerped)",
      queries.size());
  const BrunetonTextures t = bake_bruneton(atm, in.transmittance, op, BakeContext{});
  BrunetonTextures half = t;
  half.scattering = half_round_trip(t.scattering);
  half.single_mie = half_round_trip(t.single_mie);
  out["half"] = {{"float", measure(atm, t, queries)},
                 {"half", measure(atm, half, queries)},
                 {"storage", half_storage_stats(t.scattering)}};
  return out;
}

}  // namespace skybake

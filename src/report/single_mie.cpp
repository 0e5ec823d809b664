// Single Mie (the 4D family's separate single-Mie texture) ladder of
// `skybake report` (ladders.hpp): table shapes x ray nodes, each
// texture made by the single-scattering pass of the bake
// (bake_single_scattering, the same pass and texture bake_bruneton returns
// as single_mie), read with lookup_scattering_rgb (quadrilinear, nu slices
// lerped) at pseudo-random (r, mu, mu_s, nu) and compared with adaptive
// quadrature of the Mie group's phase-free single scattering
// (reference_single_scattering_phase_free: no table, the planet's shadow
// included). Both sides are S_M without its phase; an engine multiplies
// by p_M(nu), which leaves each query's relative error unchanged.
//
// Queries as the scattering ladder's: altitude top * u^2, mu uniform in
// [-1, 1], mu_s uniform in [mu_s_min, 1], the azimuth between view and sun
// uniform.
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/scattering.hpp"
#include "report/single_mie.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct MieQuery {
  double r = 0.0, mu = 0.0, mu_s = 0.0, nu = 0.0;
  bool hits_ground = false;
  glm::dvec3 reference{0.0};  // S_M, phase-free
};

std::vector<MieQuery> single_mie_queries(const ReportInputs& in, int count, double mu_s_min) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<MieQuery> q(static_cast<size_t>(count));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const ViewQuery v = view_query(atm, i, kSingleMieQueryDim, mu_s_min);
    q[i].r = v.r, q[i].mu = v.mu, q[i].mu_s = v.mu_s, q[i].nu = v.nu;
    q[i].hits_ground = v.hits_ground;
    q[i].reference = reference_single_scattering_phase_free(atm, q[i].r, q[i].mu, q[i].mu_s,
                                                            q[i].nu, ScatteringGroup::mie,
                                                            in.level.single_scattering_tolerance)
                         .value;
  });
  return q;
}

ErrorStats measure(const Atmosphere& atm, const Texture& single_mie, const ScatteringShape& shape,
                   const std::vector<MieQuery>& queries) {
  ErrorTally tally;
  for (const MieQuery& q : queries) {
    const glm::dvec3 v =
        lookup_scattering_rgb(single_mie, shape, atm, q.r, q.mu, q.mu_s, q.nu, q.hits_ground);
    for (int c = 0; c < 3; ++c) tally.add(v[c], q.reference[c]);
  }
  return tally.stats();
}

}  // namespace

// The scattering ladder's points: both textures come from the same pass.
SingleMieSetup SingleMieSetup::full() {
  SingleMieSetup s;
  s.single_mie_shapes = ScatteringSetup::full().scattering_shapes;
  s.single_mie_ray_nodes = ScatteringSetup::full().scattering_ray_nodes;
  s.single_mie_queries = 1024;
  return s;
}

SingleMieSetup SingleMieSetup::quick() {
  SingleMieSetup s;
  s.single_mie_shapes = ScatteringSetup::quick().scattering_shapes;
  s.single_mie_ray_nodes = ScatteringSetup::quick().scattering_ray_nodes;
  s.single_mie_queries = 64;
  return s;
}

nlohmann::json single_mie_report(const ReportInputs& in, const SingleMieSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const BrunetonSpec op = bruneton_spec(operating_spec(in.scene, "scattering"));
  in.stage("single_mie: reference quadrature");
  const std::vector<MieQuery> queries =
      single_mie_queries(in, setup.single_mie_queries, op.mu_s_min);

  const auto bake = [&](const ScatteringShape& shape, int nodes) {
    return bake_single_scattering(atm, in.transmittance, shape, nodes, BakeContext{}).mie;
  };
  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& shape : setup.single_mie_shapes)
    for (int nodes : setup.single_mie_ray_nodes)
      grid.push_back({{"size", shape}, {"ray_nodes", nodes}});
  const nlohmann::json axes = {{"ray_nodes", setup.single_mie_ray_nodes},
                               {"size", setup.single_mie_shapes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    const std::vector<int> size = s["size"];
    const ScatteringShape shape{size[0], size[1], size[2], size[3], op.mu_s_min};
    Texture mie;
    const double seconds = time_bake([&] { return bake(shape, s["ray_nodes"].get<int>()); }, mie,
                                     in.level.min_timing_seconds);
    nlohmann::json point = measure(atm, mie, shape, queries).json();
    point["seconds"] = seconds;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.r_size, op.mu_size, op.mu_s_size, op.nu_size}},
                                      {"ray_nodes", op.ray_nodes}};
  nlohmann::json out = run_ladder("single_mie", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "single_mie";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "adaptive quadrature of the Mie group's phase-free single scattering "
      "(reference_single_scattering_phase_free, tolerance {:g}), independent of every table; "
      "each point runs the bake's single-scattering pass (the texture's own error: mapping, "
      "interpolation, ray quadrature)",
      in.level.single_scattering_tolerance);
  out["queries"] = fmt::format(
      "{} points: altitude top*u^2, mu uniform, mu_s uniform in [mu_s_min, 1], azimuth "
      "uniform; lookup_scattering_rgb (quadrilinear, nu slices lerped), S_M without its phase",
      queries.size());
  const ScatteringShape shape = op.shape();
  const Texture mie = bake(shape, op.ray_nodes);
  out["half"] = {{"float", measure(atm, mie, shape, queries).json()},
                 {"half", measure(atm, half_round_trip(mie), shape, queries).json()},
                 {"storage", half_storage_stats(mie)}};
  return out;
}

}  // namespace skybake

// Gathering sum (the 3D family's gathering LUT summed over orders,
// gathering_lut.hpp) ladder of `skybake report` (ladders.hpp): 3D
// table shapes (h, mu, mu_s) x gathering directions, each point one whole
// bake_scattering3d at the preset's orders (one bake makes both products,
// so its time is the product's cost), the table read with
// lookup_gathering (bilinear) at the texel centres of a reference table.
//
// The reference is a self-convergence one: the same bake, same orders, at
// a finer shape, more gathering directions and ray nodes
// (gathering_reference_*); the queries sit on its texel centres, so it is
// read without interpolation. No independent quadrature of multiple
// scattering exists here (the path tracer would need one per texel and
// order); what this measures is how far each point is from the converged
// discretisation, not the error of the model (azimuth-free orders,
// isotropic re-scattering) against the truth.
#include <fmt/format.h>

#include "atmosphere/gathering_lut.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/gathering_sum.hpp"
#include "report/ladders.hpp"
#include "report/stats.hpp"

namespace skybake {

namespace {

struct GatheringQuery {
  double h = 0.0, mu_s = 0.0;
  glm::dvec3 reference{0.0};
};

// Pseudo-random texel centres of the reference table.
std::vector<GatheringQuery> gathering_queries(const ReportInputs& in, int count,
                                              const Texture& reference) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<GatheringQuery> q(static_cast<size_t>(count));
  for (size_t i = 0; i < q.size(); ++i) {
    const int x = std::min(int(query_unit(i, 80) * reference.width), reference.width - 1);
    const int y = std::min(int(query_unit(i, 81) * reference.height), reference.height - 1);
    q[i].h = h_from_scattering3d_u(atm, texel_center(x, reference.width), reference.width);
    q[i].mu_s = mu_s_from_scattering3d_u(texel_center(y, reference.height), reference.height);
    for (int c = 0; c < 3; ++c) q[i].reference[c] = reference.at(x, y, 0, 0, c);
  }
  return q;
}

ErrorStats measure(const Atmosphere& atm, const Texture& gathering,
                   const std::vector<GatheringQuery>& queries) {
  ErrorTally tally;
  for (const GatheringQuery& q : queries) {
    const glm::dvec3 g = lookup_gathering(gathering, atm, q.h, q.mu_s);
    for (int c = 0; c < 3; ++c) tally.add(g[c], q.reference[c]);
  }
  return tally.stats();
}

}  // namespace

GatheringSumSetup GatheringSumSetup::full() {
  GatheringSumSetup s;
  s.gathering_shapes = {{8, 32, 8}, {16, 64, 16}, {32, 128, 32}};
  s.gathering_directions = {4, 8, 16, 32};
  s.gathering_queries = 512;
  s.gathering_reference_shape = {64, 256, 64};
  s.gathering_reference_directions = 64;
  s.gathering_reference_ray_nodes = 99;
  return s;
}

GatheringSumSetup GatheringSumSetup::quick() {
  GatheringSumSetup s;
  s.gathering_shapes = {{8, 32, 8}, {16, 64, 16}};
  s.gathering_directions = {4, 16};
  s.gathering_queries = 128;
  s.gathering_reference_shape = {48, 192, 48};
  s.gathering_reference_directions = 32;
  s.gathering_reference_ray_nodes = 99;
  return s;
}

nlohmann::json gathering_sum_report(const ReportInputs& in, const GatheringSumSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const Scattering3dSpec op = scattering3d_spec(operating_spec(in.scene, "scattering3d"));
  const auto bake = [&](const std::vector<int>& shape, int directions, int nodes) {
    Scattering3dSpec spec = op;
    spec.height_size = shape.at(0);
    spec.view_size = shape.at(1);
    spec.sun_size = shape.at(2);
    spec.gathering_directions = directions;
    spec.ray_nodes = nodes;
    return bake_scattering3d(atm, in.transmittance, spec, BakeContext{});
  };
  in.stage("gathering_sum: reference bake");
  const Scattering3dTextures reference =
      bake(setup.gathering_reference_shape, setup.gathering_reference_directions,
           setup.gathering_reference_ray_nodes);
  const std::vector<GatheringQuery> queries =
      gathering_queries(in, setup.gathering_queries, reference.gathering_sum);

  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& shape : setup.gathering_shapes)
    for (int directions : setup.gathering_directions)
      grid.push_back({{"size", shape}, {"directions", directions}});
  const nlohmann::json axes = {{"directions", setup.gathering_directions},
                               {"size", setup.gathering_shapes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    Scattering3dTextures t;
    const double seconds = time_bake(
        [&] {
          return bake(s["size"].get<std::vector<int>>(), s["directions"].get<int>(), op.ray_nodes);
        },
        t, in.level.min_timing_seconds);
    nlohmann::json point = measure(atm, t.gathering_sum, queries).json();
    point["seconds"] = seconds;
    point["orders_used"] = t.orders_used;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.height_size, op.view_size, op.sun_size}},
                                      {"directions", op.gathering_directions}};
  nlohmann::json out = run_ladder("gathering_sum", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "gathering_sum";
  out["kind"] = "lut";
  const std::vector<int>& rs = setup.gathering_reference_shape;
  out["reference"] = fmt::format(
      "self-convergence: the same bake ({}) at {}x{}x{} with {} gathering directions and {} "
      "ray nodes, read at its texel centres; measures the distance to the converged "
      "discretisation, not the azimuth-free model's error",
      op.tolerance > 0.0 ? fmt::format("orders until a residual below {:g}", op.tolerance)
                         : fmt::format("{} orders", op.orders),
      rs.at(0), rs.at(1), rs.at(2), setup.gathering_reference_directions,
      setup.gathering_reference_ray_nodes);
  out["queries"] = fmt::format(
      "{} texel centres of the reference table, uniform over its (h, mu_s) texels; "
      "lookup_gathering (bilinear)",
      queries.size());
  const Texture table =
      bake({op.height_size, op.view_size, op.sun_size}, op.gathering_directions, op.ray_nodes)
          .gathering_sum;
  out["half"] = {{"float", measure(atm, table, queries).json()},
                 {"half", measure(atm, half_round_trip(table), queries).json()},
                 {"storage", half_storage_stats(table)}};
  return out;
}

}  // namespace skybake

// Transmittance ladder of `skybake report` (ladders.hpp): steps x
// sizes, each table read with lookup_transmittance_to_top at pseudo-random
// (r, mu) against adaptive quadrature of the optical depth.
//
// Query points are uniform in the table's own unit square (x_mu, x_r) of
// transmittance_lut.hpp: the domain the table covers, with the measure its
// mapping chose (dense near the ground and the horizon, where transmittance
// changes fastest), so every part of the table is probed.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/transmittance.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct TransmittanceQuery {
  double r = 0.0, mu = 0.0;
  glm::dvec3 reference{0.0};
};

std::vector<TransmittanceQuery> transmittance_queries(const ReportInputs& in, int count) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<TransmittanceQuery> q(static_cast<size_t>(count));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const RadiusCosine point = transmittance_query(atm, i);
    q[i].r = point.r;
    q[i].mu = point.mu;
    q[i].reference =
        reference_transmittance_to_top(atm, q[i].r, q[i].mu, in.level.quadrature_tolerance).value;
  });
  return q;
}

ErrorStats measure(const Texture& lut, const Atmosphere& atm,
                   const std::vector<TransmittanceQuery>& queries) {
  ErrorTally tally;
  for (const TransmittanceQuery& q : queries) {
    const glm::dvec3 t = lookup_transmittance_to_top(lut, atm, q.r, q.mu);
    for (int c = 0; c < 3; ++c) tally.add(t[c], q.reference[c]);
  }
  return tally.stats();
}

nlohmann::json settings_of(const TransmittanceLutSpec& s) {
  return {{"size", {s.width, s.height}}, {"steps", s.steps}};
}

}  // namespace

TransmittanceSetup TransmittanceSetup::full() {
  TransmittanceSetup s;
  s.transmittance_steps = {1, 2, 3, 6, 12};
  s.transmittance_sizes = {{64, 16}, {128, 32}, {256, 64}, {512, 128}};
  s.transmittance_queries = 4096;
  return s;
}

TransmittanceSetup TransmittanceSetup::quick() {
  TransmittanceSetup s;
  s.transmittance_steps = {1, 2, 3, 6};
  s.transmittance_sizes = {{64, 16}, {256, 64}};
  s.transmittance_queries = 512;
  return s;
}

nlohmann::json transmittance_report(const ReportInputs& in, const TransmittanceSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  in.stage("transmittance: reference quadrature");
  const std::vector<TransmittanceQuery> queries =
      transmittance_queries(in, setup.transmittance_queries);
  const TransmittanceLutSpec op = transmittance_spec(operating_spec(in.scene, "transmittance"));

  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& size : setup.transmittance_sizes)
    for (int steps : setup.transmittance_steps) grid.push_back({{"size", size}, {"steps", steps}});
  const nlohmann::json axes = {{"steps", setup.transmittance_steps},
                               {"size", setup.transmittance_sizes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    TransmittanceLutSpec spec;
    spec.width = s["size"][0];
    spec.height = s["size"][1];
    spec.steps = s["steps"];
    Texture lut;
    const double seconds =
        time_bake([&] { return bake_transmittance_lut(atm, spec, BakeContext{}); }, lut,
                  in.level.min_timing_seconds);
    nlohmann::json point = measure(lut, atm, queries).json();
    point["seconds"] = seconds;
    return point;
  };
  nlohmann::json out =
      run_ladder("transmittance", axes, grid, settings_of(op), bake_and_measure, in);
  out["product"] = "transmittance";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "adaptive Gauss-Kronrod quadrature of the optical depth (reference_transmittance_to_top), "
      "relative tolerance {:g}",
      in.level.quadrature_tolerance);
  out["queries"] = fmt::format(
      "{} points uniform in the table's (x_mu, x_r) square, 3 channels each; "
      "lookup_transmittance_to_top (bilinear)",
      queries.size());
  // The operating point's table, as baked for every other product here.
  out["half"] = {{"float", measure(in.transmittance, atm, queries).json()},
                 {"half", measure(half_round_trip(in.transmittance), atm, queries).json()},
                 {"storage", half_storage_stats(in.transmittance)}};
  return out;
}

}  // namespace skybake

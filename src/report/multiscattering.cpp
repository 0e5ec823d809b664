// Multiple-scattering ladder of `skybake report` (ladders.hpp):
// directions x steps x sizes (the preset's size first), each table read with
// lookup_multiscattering at pseudo-random (r, mu_s) against the same integral
// (compute_multiscattering, Hillaire 2020 eq. 5-10) with many more directions
// and steps (the symmetric Gauss rule, which converges near the terminator
// where the Fibonacci set does not: docs/reference.md), reading the fine
// reference transmittance table. The ladder's
// bakes read the operating-point transmittance table, as a bake would, so
// their error includes that table's (small) error.
//
// Queries: altitude uniform over the shell, sun zenith cosine uniform in
// [-1, 1] (the axes of a table whose mappings are both linear).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/multiscattering.hpp"
#include "report/stats.hpp"

namespace skybake {

namespace {

struct MultiscatteringQuery {
  double r = 0.0, mu_s = 0.0;
  glm::dvec3 reference{0.0};
};

std::vector<MultiscatteringQuery> multiscattering_queries(const ReportInputs& in,
                                                          const MultiscatteringSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<MultiscatteringQuery> q(size_t(setup.multiscattering_queries));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const RadiusCosine point = multiscattering_query(atm, i);
    q[i].r = point.r;
    q[i].mu_s = point.mu;
    q[i].reference =
        compute_multiscattering(atm, in.reference_transmittance, q[i].r, q[i].mu_s,
                                multiscattering_rule(DirectionQuadrature::symmetric_gauss,
                                                     setup.multiscattering_reference_directions,
                                                     atm, q[i].r),
                                setup.multiscattering_reference_steps)
            .psi_ms;
  });
  return q;
}

ErrorStats measure(const Texture& lut, const Atmosphere& atm,
                   const std::vector<MultiscatteringQuery>& queries) {
  ErrorTally tally;
  for (const MultiscatteringQuery& q : queries) {
    const glm::dvec3 psi = lookup_multiscattering(lut, atm, q.r, q.mu_s);
    for (int c = 0; c < 3; ++c) tally.add(psi[c], q.reference[c]);
  }
  return tally.stats();
}

}  // namespace

MultiscatteringSetup MultiscatteringSetup::full() {
  MultiscatteringSetup s;
  s.multiscattering_directions = {16, 64, 256};
  s.multiscattering_steps = {10, 20, 40};
  s.multiscattering_sizes = {{32, 32}, {64, 64}};
  s.multiscattering_queries = 128;
  s.multiscattering_reference_directions = 2048;
  s.multiscattering_reference_steps = 200;
  return s;
}

MultiscatteringSetup MultiscatteringSetup::quick() {
  MultiscatteringSetup s;
  s.multiscattering_directions = {16, 64};
  s.multiscattering_steps = {10, 20};
  s.multiscattering_sizes = {};
  s.multiscattering_queries = 24;
  s.multiscattering_reference_directions = 512;
  s.multiscattering_reference_steps = 80;
  return s;
}

nlohmann::json multiscattering_report(const ReportInputs& in, const MultiscatteringSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  in.stage("multiscattering: reference integration");
  const std::vector<MultiscatteringQuery> queries = multiscattering_queries(in, setup);
  const MultiscatteringLutSpec op =
      multiscattering_spec(operating_spec(in.scene, "multiscattering"));
  const nlohmann::json size = {op.width, op.height};
  std::vector<nlohmann::json> sizes = {size};
  for (const std::vector<int>& s : setup.multiscattering_sizes)
    if (nlohmann::json(s) != size) sizes.push_back(s);

  std::vector<nlohmann::json> grid;
  for (const nlohmann::json& s : sizes)
    for (int directions : setup.multiscattering_directions)
      for (int steps : setup.multiscattering_steps)
        grid.push_back({{"size", s}, {"directions", directions}, {"steps", steps}});
  const nlohmann::json axes = {{"directions", setup.multiscattering_directions},
                               {"steps", setup.multiscattering_steps},
                               {"size", sizes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    MultiscatteringLutSpec spec = op;
    spec.width = s["size"][0];
    spec.height = s["size"][1];
    spec.directions = s["directions"];
    spec.steps = s["steps"];
    Texture lut;
    const double seconds = time_bake(
        [&] { return bake_multiscattering_lut(atm, in.transmittance, spec, BakeContext{}); }, lut,
        in.level.min_timing_seconds);
    nlohmann::json point = measure(lut, atm, queries).json();
    point["seconds"] = seconds;
    point["fms_max"] = meta_double(lut.metadata, "fms_max");
    return point;
  };
  const nlohmann::json op_settings = {
      {"size", size}, {"directions", op.directions}, {"steps", op.steps}};
  nlohmann::json out = run_ladder("multiscattering", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "multiscattering";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "the same integral (Hillaire 2020 eq. 5-10) with {} directions of the symmetric Gauss "
      "rule and {} steps, reading a "
      "{}x{} transmittance table baked with {} steps",
      setup.multiscattering_reference_directions, setup.multiscattering_reference_steps,
      in.level.reference_transmittance_size[0], in.level.reference_transmittance_size[1],
      in.level.reference_transmittance_steps);
  out["queries"] = fmt::format(
      "{} points, altitude and sun zenith cosine uniform, 3 channels each; "
      "lookup_multiscattering (bilinear)",
      queries.size());
  out["half"] = {{"float", measure(in.multiscattering, atm, queries).json()},
                 {"half", measure(half_round_trip(in.multiscattering), atm, queries).json()},
                 {"storage", half_storage_stats(in.multiscattering)}};
  return out;
}

}  // namespace skybake

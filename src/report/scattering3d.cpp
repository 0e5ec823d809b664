// Scattering3d (the azimuth-free Elek / Frostbite table) ladder of `skybake
// report` (ladders.hpp): table shapes (h, mu, mu_s) x ray nodes,
// each baked with one order (single scattering: the part an independent
// quadrature checks) in the preset's Mie storage, read with
// lookup_scattering3d (trilinear, the phases applied at the read, Mie from
// alpha when combined) at pseudo-random (r, mu, mu_s, nu).
//
// What a texel stands for is the mean over the sun's azimuth around the
// view (scattering3d_lut.hpp): the table cannot hold the azimuth, so the
// main numbers compare with what it can hold at best,
//   p_R(nu) <S_R> + p_M(nu) <S_M>,  <S_c> = (1/pi) int_0^pi S_c(phi) d phi,
// S_c the phase-free single scattering of group c by adaptive quadrature
// (reference_single_scattering_phase_free: no table, the planet's shadow
// included), the azimuth mean by the midpoint rule on
// scattering3d_reference_azimuths points (spectral for this smooth periodic
// function, second order across a shadow edge): the table's own error
// (mapping, interpolation, ray quadrature, its 8 azimuths, Mie storage).
// "vs_single_scattering" compares the same reads with the radiance at the
// query's own azimuth (reference_single_scattering): what an engine gets,
// the azimuth-free model's error included; it does not fall with the shape.
//
// Queries: altitude top * u^2, mu uniform in [-1, 1], mu_s uniform in
// [mu_s_min, 1] of the 3D mapping, the azimuth uniform.
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/ladders.hpp"
#include "report/scattering3d.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct Scattering3dQuery {
  double h = 0.0, mu = 0.0, mu_s = 0.0, nu = 0.0;
  bool hits_ground = false;
  glm::dvec3 azimuth_mean{0.0};  // p_R <S_R> + p_M <S_M>
  glm::dvec3 radiance{0.0};      // single scattering at the query's azimuth
};

// S_R and S_M, phase-free, for the sun at azimuth phi around the view.
struct PhaseFreePair {
  glm::dvec3 rayleigh, mie;
};
PhaseFreePair phase_free_at(const Atmosphere& atm, double r, double mu, double mu_s, double phi,
                            double tol) {
  const double nu = nu_from_azimuth(mu, mu_s, phi);
  return {
      reference_single_scattering_phase_free(atm, r, mu, mu_s, nu, ScatteringGroup::rayleigh, tol)
          .value,
      reference_single_scattering_phase_free(atm, r, mu, mu_s, nu, ScatteringGroup::mie, tol)
          .value};
}

std::vector<Scattering3dQuery> scattering3d_queries(const ReportInputs& in,
                                                    const Scattering3dSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const ScatteringPhases phases = scattering_phases(atm);
  const double tol = in.level.single_scattering_tolerance;
  const int azimuths = setup.scattering3d_reference_azimuths;
  std::vector<Scattering3dQuery> q(size_t(setup.scattering3d_queries));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const ViewQuery v = view_query(atm, i, kScattering3dQueryDim, kScattering3dMuSMin);
    q[i].h = v.altitude_m, q[i].mu = v.mu, q[i].mu_s = v.mu_s, q[i].nu = v.nu;
    q[i].hits_ground = v.hits_ground;
    const double r = v.r;
    PhaseFreePair mean{glm::dvec3(0.0), glm::dvec3(0.0)};
    for (int a = 0; a < azimuths; ++a) {
      const PhaseFreePair s =
          phase_free_at(atm, r, q[i].mu, q[i].mu_s, (a + 0.5) * kPi / azimuths, tol);
      mean.rayleigh += s.rayleigh / double(azimuths);
      mean.mie += s.mie / double(azimuths);
    }
    q[i].azimuth_mean = phases.rayleigh(q[i].nu) * mean.rayleigh + phases.mie(q[i].nu) * mean.mie;
    q[i].radiance = reference_single_scattering(atm, r, q[i].mu, q[i].mu_s, q[i].nu, tol).value;
  });
  return q;
}

nlohmann::json measure(const Atmosphere& atm, const Scattering3dTextures& t,
                       const std::vector<Scattering3dQuery>& queries) {
  const Texture no_mie;
  const Texture& mie = t.scattering.channel_count() >= 4 ? no_mie : t.mie;
  ErrorTally mean, model;
  for (const Scattering3dQuery& q : queries) {
    const glm::dvec3 v = lookup_scattering3d(t.scattering, mie, t.shape, atm, q.h, q.mu, q.mu_s,
                                             q.nu, q.hits_ground);
    for (int c = 0; c < 3; ++c) {
      mean.add(v[c], q.azimuth_mean[c]);
      model.add(v[c], q.radiance[c]);
    }
  }
  nlohmann::json j = mean.stats().json();
  j["vs_single_scattering"] = model.stats().json();
  return j;
}

}  // namespace

Scattering3dSetup Scattering3dSetup::full() {
  Scattering3dSetup s;
  s.scattering3d_shapes = {{8, 32, 8}, {16, 64, 16}, {32, 128, 32}, {64, 256, 64}};
  s.scattering3d_ray_nodes = {15, 30, 51, 99};
  s.scattering3d_queries = 1024;
  s.scattering3d_reference_azimuths = 32;
  return s;
}

Scattering3dSetup Scattering3dSetup::quick() {
  Scattering3dSetup s;
  s.scattering3d_shapes = {{8, 32, 8}, {16, 64, 16}};
  s.scattering3d_ray_nodes = {15, 51};
  s.scattering3d_queries = 64;
  s.scattering3d_reference_azimuths = 16;
  return s;
}

nlohmann::json scattering3d_report(const ReportInputs& in, const Scattering3dSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  Scattering3dSpec op = scattering3d_spec(operating_spec(in.scene, "scattering3d"));
  op.orders = 1;
  op.tolerance = 0.0;
  in.stage("scattering3d: reference quadrature (azimuth means)");
  const std::vector<Scattering3dQuery> queries = scattering3d_queries(in, setup);

  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& shape : setup.scattering3d_shapes)
    for (int nodes : setup.scattering3d_ray_nodes)
      grid.push_back({{"size", shape}, {"ray_nodes", nodes}});
  const nlohmann::json axes = {{"ray_nodes", setup.scattering3d_ray_nodes},
                               {"size", setup.scattering3d_shapes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    Scattering3dSpec spec = op;
    spec.height_size = s["size"][0];
    spec.view_size = s["size"][1];
    spec.sun_size = s["size"][2];
    spec.ray_nodes = s["ray_nodes"];
    Scattering3dTextures t;
    const double seconds =
        time_bake([&] { return bake_scattering3d(atm, in.transmittance, spec, BakeContext{}); }, t,
                  in.level.min_timing_seconds);
    nlohmann::json point = measure(atm, t, queries);
    point["seconds"] = seconds;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.height_size, op.view_size, op.sun_size}},
                                      {"ray_nodes", op.ray_nodes}};
  nlohmann::json out = run_ladder("scattering3d", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "scattering3d";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "the mean over {} sun azimuths of adaptive quadrature of phase-free single scattering per "
      "group (reference_single_scattering_phase_free, tolerance {:g}), with the phases at the "
      "query's nu: the best an azimuth-free table can hold, independent of every table; each "
      "point bakes one order (the table's own error: mapping, interpolation, ray quadrature, "
      "{} azimuth samples, Mie storage '{}'); vs_single_scattering: the same reads against the "
      "radiance at the query's own azimuth (reference_single_scattering), the model's error "
      "included",
      setup.scattering3d_reference_azimuths, in.level.single_scattering_tolerance,
      op.azimuth_samples, op.combined_mie_alpha ? "alpha" : "separate");
  out["queries"] = fmt::format(
      "{} points: altitude top*u^2, mu uniform, mu_s uniform in [mu_s_min, 1] of the 3D "
      "mapping, azimuth uniform; lookup_scattering3d (trilinear)",
      queries.size());
  const Scattering3dTextures t = bake_scattering3d(atm, in.transmittance, op, BakeContext{});
  Scattering3dTextures half = t;
  half.scattering = half_round_trip(t.scattering);
  half.mie = half_round_trip(t.mie);
  out["half"] = {{"float", measure(atm, t, queries)},
                 {"half", measure(atm, half, queries)},
                 {"storage", half_storage_stats(t.scattering)}};
  return out;
}

}  // namespace skybake

// Irradiance (Bruneton's ground irradiance) ladder of `skybake report`
// (ladders.hpp): table sizes (mu_s, r) x hemisphere directions. Each
// table is baked from one scattering order, the single scattering of a 4D
// table at the preset's scattering shape and ray nodes (baked once, as a
// bake reads the operating-point tables), plus direct sunlight when the
// product has include_direct (irradiance_lut.hpp); it is read with
// lookup_irradiance at pseudo-random (r, mu_s) against references that read
// no table:
//   direct    E_0 = E_sun T(r, mu_s) c(mu_s), T by adaptive quadrature of
//             the optical depth (reference_transmittance_to_top) and c the
//             closed-form sun-disk average the bake defines
//             (sun_average_cosine, Bruneton 2017 ComputeDirectIrradiance);
//   indirect  E_1 = int over the upper hemisphere of L_1 cos(theta) d omega,
//             L_1 by adaptive quadrature of single scattering
//             (reference_single_scattering), the hemisphere by nested adaptive
//             Gauss-Kronrod over mu = cos(theta) in [0, 1] (cut at mu = mu_s,
//             under Mie's forward peak) and the azimuth from the sun's
//             vertical plane in [0, pi] (the sky is symmetric about it).
// So a point's error is the table's own: bilinear interpolation, the bake's
// hemisphere quadrature, and the error of the 4D table it integrates (which
// the scattering ladder measures). Orders >= 2 add a smoother sky to the
// same integral; they are not measured here.
//
// The main numbers compare what the table holds (E_1, or E_0 + E_1 with
// include_direct); "ground_total" compares E_0 + E_1 as an engine gets it
// (the table, plus E_0 from the operating-point transmittance LUT at run
// time when the table is indirect only).
//
// Queries: altitude top * u^2 (terrain sits low), mu_s uniform in
// [mu_s_min, 1] of the 4D table (below it the table's sky is clamped).
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/irradiance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product_graph.hpp"
#include "report/irradiance.hpp"
#include "report/ladders.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

struct IrradianceQuery {
  double r = 0.0, mu_s = 0.0;
  glm::dvec3 direct{0.0}, indirect{0.0};  // references E_0 and E_1
};

// E_1 of the opening comment. The inner single-scattering quadratures get
// a tenth of the hemisphere's tolerance; the absolute floor (1e-3 tol of
// the sun's illuminance) stops the refinement of a sky that is nearly black.
glm::dvec3 reference_indirect_irradiance(const Atmosphere& atm, double r, double mu_s, double tol) {
  QuadratureOptions options;
  options.relative_tolerance = tol;
  options.absolute_tolerance =
      1e-3 * tol *
      std::max(atm.sun_illuminance.x, std::max(atm.sun_illuminance.y, atm.sun_illuminance.z));
  const double sin_s = safe_sqrt(1.0 - mu_s * mu_s);
  const auto over_azimuth = [&](double mu) {
    const double sin_t = safe_sqrt(1.0 - mu * mu);
    const auto radiance = [&](double phi) {
      const double nu = clamp_cosine(mu * mu_s + sin_t * sin_s * std::cos(phi));
      return reference_single_scattering(atm, r, mu, mu_s, nu, 0.1 * tol).value;
    };
    return 2.0 * mu * integrate_adaptive(radiance, 0.0, kPi, options).value;
  };
  return integrate_adaptive(over_azimuth, 0.0, 1.0, options, {mu_s}).value;
}

std::vector<IrradianceQuery> irradiance_queries(const ReportInputs& in,
                                                const IrradianceSetup& setup, double mu_s_min) {
  const Atmosphere& atm = in.scene.atmosphere;
  std::vector<IrradianceQuery> q(size_t(setup.irradiance_queries));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const RadiusCosine point = irradiance_query(atm, i, mu_s_min);
    q[i].r = point.r;
    q[i].mu_s = point.mu;
    const double c = sun_average_cosine(q[i].mu_s, atm.sun_angular_radius_rad);
    if (c > 0.0)
      q[i].direct =
          atm.sun_illuminance * c *
          reference_transmittance_to_top(atm, q[i].r, q[i].mu_s, in.level.quadrature_tolerance)
              .value;
    q[i].indirect =
        reference_indirect_irradiance(atm, q[i].r, q[i].mu_s, setup.irradiance_reference_tolerance);
  });
  return q;
}

nlohmann::json measure(const Texture& table, bool includes_direct, const ReportInputs& in,
                       const std::vector<IrradianceQuery>& queries) {
  const Atmosphere& atm = in.scene.atmosphere;
  ErrorTally held, total;
  for (const IrradianceQuery& q : queries) {
    const glm::dvec3 e = lookup_irradiance(table, atm, q.r, q.mu_s);
    const glm::dvec3 direct = includes_direct
                                  ? glm::dvec3(0.0)
                                  : compute_direct_irradiance(atm, in.transmittance, q.r, q.mu_s);
    for (int c = 0; c < 3; ++c) {
      held.add(e[c], q.indirect[c] + (includes_direct ? q.direct[c] : 0.0));
      total.add(e[c] + direct[c], q.indirect[c] + q.direct[c]);
    }
  }
  nlohmann::json j = held.stats().json();
  j["ground_total"] = total.stats().json();
  return j;
}

}  // namespace

IrradianceSetup IrradianceSetup::full() {
  IrradianceSetup s;
  s.irradiance_sizes = {{16, 4}, {32, 8}, {64, 16}, {128, 32}};
  s.irradiance_directions = {8, 16, 32, 64};
  s.irradiance_queries = 256;
  s.irradiance_reference_tolerance = 1e-4;
  return s;
}

IrradianceSetup IrradianceSetup::quick() {
  IrradianceSetup s;
  s.irradiance_sizes = {{16, 4}, {64, 16}};
  s.irradiance_directions = {8, 32};
  s.irradiance_queries = 16;
  s.irradiance_reference_tolerance = 1e-3;
  return s;
}

nlohmann::json irradiance_report(const ReportInputs& in, const IrradianceSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const OutputSpec product = operating_spec(in.scene, "irradiance");
  const bool includes_direct = product.options.value("include_direct", false);
  const BrunetonSpec family = bruneton_spec(operating_spec(in.scene, "scattering"));
  const ScatteringShape shape = family.shape();
  in.stage("irradiance: single scattering of the 4D table");
  const ScatteringPhases phases = scattering_phases(atm);
  const SingleScatteringTables single =
      bake_single_scattering(atm, in.transmittance, shape, family.ray_nodes, BakeContext{});
  const ScatteringOrder order1{&single.rayleigh, &single.mie, nullptr, &phases};
  in.stage("irradiance: reference quadrature over the hemisphere");
  const std::vector<IrradianceQuery> queries = irradiance_queries(in, setup, shape.mu_s_min);

  const auto bake = [&](int width, int height, int directions) {
    Texture e =
        bake_indirect_irradiance(atm, shape, order1, width, height, directions, BakeContext{});
    if (includes_direct) {
      const Texture direct =
          bake_direct_irradiance(atm, in.transmittance, width, height, BakeContext{});
      for (size_t i = 0; i < e.data.size(); ++i) e.data[i] += direct.data[i];
    }
    return e;
  };
  std::vector<nlohmann::json> grid;
  for (const std::vector<int>& size : setup.irradiance_sizes)
    for (int directions : setup.irradiance_directions)
      grid.push_back({{"size", size}, {"directions", directions}});
  const nlohmann::json axes = {{"directions", setup.irradiance_directions},
                               {"size", setup.irradiance_sizes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    Texture table;
    const double seconds = time_bake(
        [&] {
          return bake(s["size"][0].get<int>(), s["size"][1].get<int>(), s["directions"].get<int>());
        },
        table, in.level.min_timing_seconds);
    nlohmann::json point = measure(table, includes_direct, in, queries);
    point["seconds"] = seconds;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {product.size.at(0), product.size.at(1)}},
                                      {"directions", family.irradiance_directions}};
  nlohmann::json out = run_ladder("irradiance", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "irradiance";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "no table: {}E_1 = the upper hemisphere's integral of single-scattered radiance times "
      "cos(theta), nested adaptive Gauss-Kronrod (relative tolerance {:g}) over "
      "reference_single_scattering; each point bakes the table from one order (single "
      "scattering of the preset's {}x{}x{}x{} 4D table, baked once: its own error is the "
      "scattering ladder's){}; ground_total: direct + indirect as an engine sums them",
      includes_direct ? "E_0 = E_sun T c(mu_s), T by adaptive quadrature, c the bake's "
                        "sun-disk average (Bruneton 2017), plus "
                      : "",
      setup.irradiance_reference_tolerance, shape.r_size, shape.mu_size, shape.mu_s_size,
      shape.nu_size,
      includes_direct ? ", plus direct sunlight"
                      : "; the table holds indirect light only (include_direct false), "
                        "E_0 is added at run time from the transmittance LUT");
  out["queries"] = fmt::format(
      "{} points: altitude top*u^2, mu_s uniform in [mu_s_min, 1] of the 4D table; "
      "lookup_irradiance (bilinear)",
      queries.size());
  const Texture table = bake(product.size.at(0), product.size.at(1), family.irradiance_directions);
  out["half"] = {{"float", measure(table, includes_direct, in, queries)},
                 {"half", measure(half_round_trip(table), includes_direct, in, queries)},
                 {"storage", half_storage_stats(table)}};
  return out;
}

}  // namespace skybake

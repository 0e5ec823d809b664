#include "report/bruneton.hpp"

#include "pipeline/atmosphere_specs.hpp"

#include <chrono>
#include <cmath>
#include <iterator>
#include <map>

#include <fmt/format.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/orders_resolution.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/math.hpp"
#include "pipeline/product_graph.hpp"
#include "report/sky_radiance.hpp"

namespace skybake {

namespace {


BrunetonSpec level_bruneton_spec(const BrunetonSetup& setup, const Atmosphere& atm) {
  const std::vector<int>& shape =
      !setup.bruneton_shape_mie_lobe.empty() && mie_shapes_multiple_scattering(atm)
          ? setup.bruneton_shape_mie_lobe
          : setup.bruneton_shape;
  BrunetonSpec b;
  b.r_size = shape.at(0);
  b.mu_size = shape.at(1);
  b.mu_s_size = shape.at(2);
  b.nu_size = shape.at(3);
  b.orders = setup.bruneton_orders;
  b.tolerance = setup.bruneton_tolerance;
  b.max_orders = setup.bruneton_max_orders;
  return b;
}

glm::dvec3 rgb_of(const nlohmann::json& v) {
  return {v[0], v[1], v[2]};
}

// The 4D tables compared, and order 1 alone as bake_bruneton made it (same
// shape, nodes and transmittance): the table minus it is orders >= 2.
struct BakedTables {
  bool own = false;  // the scene's scattering output, else the setup's table
  BrunetonSpec spec;
  BrunetonTextures tables;
  SingleScatteringTables single;
  double seconds = 0.0;
};

BakedTables bake_tables(const ReportInputs& in, const BrunetonSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  BakedTables t;
  const OutputSpec* own = in.scene.find_output("scattering");
  t.own = own != nullptr;
  t.spec = own ? bruneton_spec(*own) : level_bruneton_spec(setup, atm);
  const BrunetonSpec& spec = t.spec;
  in.stage(fmt::format("Bruneton tables {}x{}x{}x{}, {}", spec.r_size, spec.mu_size, spec.mu_s_size,
                       spec.nu_size,
                       spec.tolerance > 0 ? fmt::format("orders to {:g}", spec.tolerance)
                                          : fmt::format("{} orders", spec.orders)));
  const auto t0 = std::chrono::steady_clock::now();
  t.tables = bake_bruneton(atm, in.transmittance, spec, BakeContext{});
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.single =
      bake_single_scattering(atm, in.transmittance, t.tables.shape, spec.ray_nodes, BakeContext{});
  return t;
}

// The three readings of the tables against the path tracer, over every view
// and per sun elevation.
struct Readings {
  std::vector<RadiancePair> all, exact_mie, hybrid;
  std::map<double, std::vector<RadiancePair>> by_sun, hybrid_by_sun;
  nlohmann::json views = nlohmann::json::array();
};

Readings read_views(const ReportInputs& in, const BakedTables& t,
                    const nlohmann::json& sky_radiance) {
  const Atmosphere& atm = in.scene.atmosphere;
  const BrunetonTextures& tables = t.tables;
  // An engine with the combined texture extrapolates single Mie from alpha.
  const Texture no_texture;
  const Texture& single_mie = t.spec.combined_mie_alpha ? no_texture : tables.single_mie;
  const double r = atm.bottom_radius_m + sky_radiance["camera_altitude_m"].get<double>();
  Readings out;
  for (const nlohmann::json& v : sky_radiance["views"]) {
    const double e = v["view_elevation_deg"].get<double>() * kDeg;
    const double phi = v["view_azimuth_deg"].get<double>() * kDeg;
    const double s = v["sun_elevation_deg"].get<double>() * kDeg;
    const glm::dvec3 dir(std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e));
    const glm::dvec3 sun(std::cos(s), 0.0, std::sin(s));
    const double mu = dir.z, mu_s = sun.z, nu = glm::dot(dir, sun);
    const bool hits = ray_intersects_ground(atm.bottom_radius_m, r, mu);
    const glm::dvec3 l =
        lookup_scattering(tables.scattering, single_mie, tables.shape, atm, r, mu, mu_s, nu, hits);
    const glm::dvec3 pt = rgb_of(v["path_traced"]), ci95 = rgb_of(v["path_traced_ci95"]);
    const RadiancePair pair{l, pt, ci95, pt};
    // The same table with single Mie read from its own texture: what the
    // alpha channel's extrapolation costs.
    const glm::dvec3 exact = lookup_scattering(tables.scattering, tables.single_mie, tables.shape,
                                               atm, r, mu, mu_s, nu, hits);
    out.exact_mie.push_back({exact, pt, ci95, pt});
    // Single scattering marched in the sky-view table (Psi_ms = 0) plus the
    // 4D table's orders >= 2: the exact-Mie read minus the single-scattering
    // tables read with the same taps, so the difference is the interpolated
    // multiple scattering.
    const glm::dvec3 multiple = exact - lookup_scattering(t.single.rayleigh, t.single.mie,
                                                          tables.shape, atm, r, mu, mu_s, nu, hits);
    const glm::dvec3 h = rgb_of(v["lut_single"]) + glm::max(multiple, 0.0);
    const RadiancePair hybrid_pair{h, pt, ci95, pt};
    out.all.push_back(pair);
    out.hybrid.push_back(hybrid_pair);
    const double sun_elevation = v["sun_elevation_deg"];
    out.by_sun[sun_elevation].push_back(pair);
    out.hybrid_by_sun[sun_elevation].push_back(hybrid_pair);
    out.views.push_back({{"sun_elevation_deg", v["sun_elevation_deg"]},
                         {"view_elevation_deg", v["view_elevation_deg"]},
                         {"view_azimuth_deg", v["view_azimuth_deg"]},
                         {"bruneton", {l.x, l.y, l.z}},
                         {"skyview_single_plus_bruneton_multiple", {h.x, h.y, h.z}}});
  }
  return out;
}

}  // namespace

BrunetonSetup BrunetonSetup::full() {
  BrunetonSetup s;
  s.bruneton_shape = {32, 128, 32, 8};
  s.bruneton_shape_mie_lobe.assign(std::begin(kMieLobeShape), std::end(kMieLobeShape));
  s.bruneton_orders = 4;
  s.bruneton_tolerance = 1e-3;
  s.bruneton_max_orders = 100;
  return s;
}

BrunetonSetup BrunetonSetup::quick() {
  BrunetonSetup s = full();
  s.bruneton_shape = {16, 64, 16, 4};
  s.bruneton_shape_mie_lobe.clear();
  s.bruneton_orders = 4;
  s.bruneton_tolerance = 0.0;
  return s;
}

nlohmann::json bruneton_comparison_report(const ReportInputs& in, const BrunetonSetup& setup) {
  const nlohmann::json& sky_radiance = in.report.at("sky_radiance");
  if (sky_radiance.is_null())
    return {{"status", "not run"}, {"reason", "the sky radiance section was not run"}};
  const BakedTables t = bake_tables(in, setup);
  Readings r = read_views(in, t, sky_radiance);
  nlohmann::json sun_stats = nlohmann::json::array();
  for (double elevation : sky_radiance["sun_elevations_deg"])
    sun_stats.push_back(
        {{"sun_elevation_deg", elevation},
         {"bruneton", radiance_stats(r.by_sun[elevation])},
         {"skyview_single_plus_bruneton_multiple", radiance_stats(r.hybrid_by_sun[elevation])}});
  const nlohmann::json stats = radiance_stats(r.all), exact_mie_stats = radiance_stats(r.exact_mie),
                       hybrid_stats = radiance_stats(r.hybrid);
  const BrunetonSpec& spec = t.spec;
  return {{"status", "measured"},
          {"bruneton",
           {{"source", t.own ? "the scene's scattering output" : "the report level's table"},
            {"shape", {spec.r_size, spec.mu_size, spec.mu_s_size, spec.nu_size}},
            {"orders", spec.orders},
            {"tolerance", spec.tolerance},
            {"orders_used", t.tables.orders_used},
            {"last_residual", t.tables.last_residual},
            {"mie", spec.combined_mie_alpha ? "alpha" : "separate"},
            {"bake_seconds", t.seconds}}},
          {"hillaire", sky_radiance["multiple"]},
          {"bruneton_vs_path_tracer", stats},
          {"target", target_json(stats)},
          {"exact_mie_target", target_json(exact_mie_stats)},
          {"bruneton_by_sun", sun_stats},
          {"bruneton_exact_mie_vs_path_tracer", exact_mie_stats},
          {"skyview_single_plus_bruneton_multiple_vs_path_tracer", hybrid_stats},
          {"hybrid_target", target_json(hybrid_stats)},
          {"views", std::move(r.views)}};
}

}  // namespace skybake

// The measured error of Bruneton's 4D family (error_measures.hpp): the
// scattering table through its single-scattering order (the bake's first
// pass, kept by bake_bruneton), the irradiance table baked again from that
// order alone, the single-Mie texture as baked (it is single scattering).
// References: single scattering integrated without a table
// (direct_single_scattering.hpp) for the 4D reads; for irradiance the
// order's hemisphere integral with 4x the directions (+ direct sunlight from
// the optical depth integrated from scratch), at off-texel points.
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/bruneton_families.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/product_graph.hpp"
#include "verify/direct_single_scattering.hpp"
#include "verify/query_points.hpp"

namespace skybake {

namespace {

// The report's --quick counts (report/scattering.cpp, single_mie.cpp,
// irradiance.cpp use 64, 64 and 16; irradiance's reference here is cheap).
constexpr int kScatteringQueries = 64;
constexpr int kIrradianceQueries = 16;
constexpr int kIrradianceDirectionFactor = 4;
constexpr int kDirectTransmittanceSteps = 200;
const DirectScatteringSteps kDirectSteps{32, 16};

std::string direct_reference() {
  return fmt::format(
      "single scattering integrated without a table (compute_single_scattering_direct: {} "
      "segments along the view ray, {} steps per sun ray, a point sun, the planet's shadow "
      "exact)",
      kDirectSteps.view_segments, kDirectSteps.sun_steps);
}

}  // namespace

nlohmann::json measure_scattering_error(const Scene& scene, const OutputSpec&,
                                        const ProductInputs& in, const Texture&) {
  const Atmosphere& atm = scene.atmosphere;
  const auto family = bruneton_family(scene, in, BakeContext{});
  const FirstOrder order1 = first_order(*family);
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringShape shape = family->shape;
  QueryReads reads(kScatteringQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const ViewQuery q = view_query(atm, i, kScatteringQueryDim, shape.mu_s_min);
    reads[i].first = lookup_scattering(order1.table, order1.separate_mie, shape, atm, q.r, q.mu,
                                       q.mu_s, q.nu, q.hits_ground);
    const SingleScattering s =
        compute_single_scattering_direct(atm, q.r, q.mu, q.mu_s, q.nu, kDirectSteps);
    reads[i].second = phases.rayleigh(q.nu) * s.rayleigh + phases.mie(q.nu) * s.mie;
  });
  return error_record(
      reads, fmt::format(
                 "lookup_scattering (quadrilinear, Mie {}) of the table's single-scattering "
                 "order (the bake's first pass, stored as the table) at points uniform in "
                 "altitude^(1/2), mu, mu_s and azimuth, against {}; orders >= 2 are not "
                 "measured",
                 order1.separate_mie.data.empty() ? "from alpha" : "separate", direct_reference()));
}

nlohmann::json measure_single_mie_error(const Scene& scene, const OutputSpec&, const ProductInputs&,
                                        const Texture& single_mie) {
  const Atmosphere& atm = scene.atmosphere;
  const ScatteringShape shape = scattering_shape_from_metadata(single_mie.metadata);
  QueryReads reads(kScatteringQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const ViewQuery q = view_query(atm, i, kSingleMieQueryDim, shape.mu_s_min);
    reads[i].first =
        lookup_scattering_rgb(single_mie, shape, atm, q.r, q.mu, q.mu_s, q.nu, q.hits_ground);
    reads[i].second =
        compute_single_scattering_direct(atm, q.r, q.mu, q.mu_s, q.nu, kDirectSteps).mie;
  });
  return error_record(reads,
                      fmt::format("lookup_scattering_rgb (quadrilinear) of the texture as baked "
                                  "at points uniform in altitude^(1/2), mu, mu_s and azimuth, "
                                  "against the Mie group of {}, both without p_M",
                                  direct_reference()));
}

nlohmann::json measure_irradiance_error(const Scene& scene, const OutputSpec& spec,
                                        const ProductInputs& in, const Texture& baked) {
  const Atmosphere& atm = scene.atmosphere;
  const Texture& t_lut = *in.at("transmittance");
  const auto family = bruneton_family(scene, in, BakeContext{});
  const bool with_direct = spec.options.value("include_direct", false);
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringShape shape = family->shape;
  const ScatteringOrder order1{&family->single_rayleigh, &family->single_mie, nullptr, &phases};
  const OutputSpec* scattering = scene.find_output("scattering");
  const int directions =
      bruneton_spec(scattering ? *scattering : default_spec(*find_product("scattering")))
          .irradiance_directions;
  Texture table = bake_indirect_irradiance(atm, shape, order1, baked.width, baked.height,
                                           directions, BakeContext{});
  if (with_direct) {
    const Texture direct = bake_direct_irradiance(atm, t_lut, baked.width, baked.height, {});
    for (size_t i = 0; i < table.data.size(); ++i) table.data[i] += direct.data[i];
  }
  QueryReads reads(kIrradianceQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const RadiusCosine q = irradiance_query(atm, i, shape.mu_s_min);
    reads[i].first = lookup_irradiance(table, atm, q.r, q.mu);
    reads[i].second = compute_indirect_irradiance(atm, shape, order1, q.r, q.mu,
                                                  kIrradianceDirectionFactor * directions);
    // A point sun below the horizon is blocked (the bake's disk fades there).
    if (with_direct && !ray_intersects_ground(atm.bottom_radius_m, q.r, q.mu))
      reads[i].second += atm.sun_illuminance *
                         sun_average_cosine(q.mu, atm.sun_angular_radius_rad) *
                         compute_transmittance_to_top(atm, q.r, q.mu, kDirectTransmittanceSteps);
  });
  return error_record(
      reads,
      fmt::format("lookup_irradiance (bilinear) of the table baked from the single-scattering "
                  "order{} at points uniform in altitude^(1/2) and mu_s, against the same "
                  "hemisphere integral with {} directions{}; orders >= 2 are not measured",
                  with_direct ? " plus direct sunlight" : "",
                  kIrradianceDirectionFactor * directions,
                  with_direct ? " plus direct sunlight from the optical depth integrated "
                                "from scratch"
                              : ""));
}

}  // namespace skybake

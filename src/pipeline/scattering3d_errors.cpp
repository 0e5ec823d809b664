// The measured error of the azimuth-free family (error_measures.hpp), through
// its single-scattering order (the bake's first pass, kept by
// bake_scattering3d):
// - scattering3d: lookup_scattering3d of that order against the mean over sun
//   azimuths of single scattering integrated without a table, with the
//   phases at the query's nu: what an azimuth-free texel can hold at best;
// - gathering_sum: its first term G_1, gathered from that order with the
//   table's bands and read at off-texel (h, mu_s), against the gathering at
//   those points with 4x the bands from single scattering computed at the
//   query's own altitude and sun (compute_single_scattering3d, the texel's
//   integral without the table's interpolation in h and mu_s).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/gathering_lut.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/bruneton_families.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/product_graph.hpp"
#include "verify/direct_single_scattering.hpp"
#include "verify/query_points.hpp"

namespace skybake {

namespace {

// The report's --quick counts are 64 and 128 (report/scattering3d.cpp,
// gathering_sum.cpp); a scattering3d query costs kAzimuths direct
// integrations, a gathering query view_size texel integrals. The references'
// settings move the measured error by less than 1% (tests/report/
// bake_error_test.cpp checks them against the report's quadrature).
constexpr int kScattering3dQueries = 64;
constexpr int kAzimuths = 16;
constexpr int kGatheringQueries = 32;
constexpr int kGatheringBandFactor = 2;
const DirectScatteringSteps kDirectSteps{32, 16};

// Order 1 at altitude h and sun mu_s on every view texel of `view_size`, in
// a 2 x view_size x 2 table whose two rows and two sun texels hold the same
// values: read at (h, mu_s), it interpolates in mu only.
Scattering3dOrder single_slice(const Atmosphere& atm, const Texture& t_lut,
                               const Scattering3dSpec& spec, double h, double mu_s,
                               Texture& rayleigh, Texture& mie) {
  const int n = spec.view_size;
  rayleigh = Texture(2, n, 2, 1, {"R", "G", "B"});
  mie = Texture(2, n, 2, 1, {"R", "G", "B"});
  for (int y = 0; y < n; ++y) {
    bool hits = false;
    const double mu = mu_from_scattering3d_u(atm, h, texel_center(y, n), n, hits);
    const SingleScattering s = compute_single_scattering3d(atm, t_lut, h, mu, mu_s, hits,
                                                           spec.ray_nodes, spec.azimuth_samples);
    for (int x = 0; x < 2; ++x)
      for (int z = 0; z < 2; ++z)
        for (int c = 0; c < 3; ++c) {
          rayleigh.at(x, y, z, 0, c) = float(s.rayleigh[c]);
          mie.at(x, y, z, 0, c) = float(s.mie[c]);
        }
  }
  return {&rayleigh, &mie, nullptr};
}

// G_1 on the gathering texels the queries' bilinear reads touch (the others
// stay 0): the table bake_gathering would make, where it is read.
Texture first_gathering(const Atmosphere& atm, const Texture& t_lut, const Scattering3dShape& shape,
                        const Scattering3dOrder& order1, int bands,
                        const std::vector<AltitudeSunCosine>& queries) {
  Texture g(shape.height_size, shape.sun_size, 1, 1, {"R", "G", "B"});
  std::vector<char> needed(size_t(g.width * g.height), 0);
  for (const AltitudeSunCosine& q : queries) {
    const AxisTap tx = axis_tap(scattering3d_u_from_h(atm, q.h, g.width), g.width);
    const AxisTap ty = axis_tap(scattering3d_u_from_mu_s(q.mu_s, g.height), g.height);
    for (int x : {tx.i0, tx.i1})
      for (int y : {ty.i0, ty.i1}) needed[size_t(y * g.width + x)] = 1;
  }
  tbb::parallel_for(size_t(0), needed.size(), [&](size_t i) {
    if (!needed[i]) return;
    const int x = int(i) % g.width, y = int(i) / g.width;
    const double h = h_from_scattering3d_u(atm, texel_center(x, g.width), g.width);
    const double mu_s = mu_s_from_scattering3d_u(texel_center(y, g.height), g.height);
    const glm::dvec3 v =
        compute_gathering(atm, t_lut, shape, order1, GroundLight3d{}, h, mu_s, bands).gathered;
    for (int c = 0; c < 3; ++c) g.at(x, y, 0, 0, c) = float(v[c]);
  });
  return g;
}

Scattering3dSpec spec_of_scattering3d(const Scene& scene) {
  const OutputSpec* asked = scene.find_output("scattering3d");
  return scattering3d_spec(asked ? *asked : default_spec(*find_product("scattering3d")));
}

}  // namespace

nlohmann::json measure_scattering3d_error(const Scene& scene, const OutputSpec&,
                                          const ProductInputs& in, const Texture&) {
  const Atmosphere& atm = scene.atmosphere;
  const auto family = scattering3d_family(scene, in, BakeContext{});
  const FirstOrder order1 = first_order(*family);
  const ScatteringPhases phases = scattering_phases(atm);
  QueryReads reads(kScattering3dQueries);
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const ViewQuery q = view_query(atm, i, kScattering3dQueryDim, kScattering3dMuSMin);
    reads[i].first = lookup_scattering3d(order1.table, order1.separate_mie, family->shape, atm,
                                         q.altitude_m, q.mu, q.mu_s, q.nu, q.hits_ground);
    const SingleScattering mean =
        compute_single_scattering_azimuth_mean(atm, q.r, q.mu, q.mu_s, kAzimuths, kDirectSteps);
    reads[i].second = phases.rayleigh(q.nu) * mean.rayleigh + phases.mie(q.nu) * mean.mie;
  });
  return error_record(
      reads,
      fmt::format("lookup_scattering3d (trilinear) of the table's single-scattering order (the "
                  "bake's first pass, {} azimuths per texel) at points uniform in "
                  "altitude^(1/2), mu, mu_s and azimuth, against the mean over {} sun azimuths "
                  "of single scattering integrated without a table "
                  "(compute_single_scattering_direct: {} segments per view ray, {} steps per "
                  "sun ray), the phases at the query's nu; orders >= 2 are not measured",
                  spec_of_scattering3d(scene).azimuth_samples, kAzimuths,
                  kDirectSteps.view_segments, kDirectSteps.sun_steps));
}

nlohmann::json measure_gathering_sum_error(const Scene& scene, const OutputSpec&,
                                           const ProductInputs& in, const Texture&) {
  const Atmosphere& atm = scene.atmosphere;
  const Texture& t_lut = *in.at("transmittance");
  const auto family = scattering3d_family(scene, in, BakeContext{});
  const Scattering3dSpec spec = spec_of_scattering3d(scene);
  const ScatteringPhases phases = scattering_phases(atm);
  const Scattering3dOrder order1{&family->single_rayleigh, &family->single_mie, &phases};
  const int bands = spec.gathering_directions;
  std::vector<AltitudeSunCosine> queries;
  for (size_t i = 0; i < size_t(kGatheringQueries); ++i) queries.push_back(gathering_query(atm, i));
  const Texture g1 = first_gathering(atm, t_lut, family->shape, order1, bands, queries);
  QueryReads reads(queries.size());
  tbb::parallel_for(size_t(0), reads.size(), [&](size_t i) {
    const AltitudeSunCosine& q = queries[i];
    reads[i].first = lookup_gathering(g1, atm, q.h, q.mu_s);
    Texture rayleigh, mie;
    Scattering3dOrder slice = single_slice(atm, t_lut, spec, q.h, q.mu_s, rayleigh, mie);
    slice.phases = &phases;
    const Scattering3dShape slice_shape{2, spec.view_size, 2};
    reads[i].second = compute_gathering(atm, t_lut, slice_shape, slice, GroundLight3d{}, q.h,
                                        q.mu_s, kGatheringBandFactor * bands)
                          .gathered;
  });
  return error_record(
      reads,
      fmt::format("lookup_gathering (bilinear) of the sum's first term G_1, gathered from the "
                  "table's single-scattering order with its {} bands, at points uniform in the "
                  "table's (x_h, x_mu_s) square, against the gathering with {} bands of single "
                  "scattering integrated at each point's own altitude and sun "
                  "(compute_single_scattering3d); later orders are not measured",
                  bands, kGatheringBandFactor * bands));
}

}  // namespace skybake

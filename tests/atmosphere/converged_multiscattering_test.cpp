// Tests of Psi_ms from converged multiple scattering
// (atmosphere/converged_multiscattering.hpp) against the closed forms of
// docs/reference.md "Converged Psi_ms": no medium over a black ground gives
// 0; no medium over a lit ground gives a max(mu_s, 0) / (2 pi) on the
// ground; an optically thin conservative slab gives the mean of single
// scattering over the sphere, integrated without a table.
#include "atmosphere/converged_multiscattering.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/phase.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/error_stats.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "verify/direct_single_scattering.hpp"
#include "verify/query_points.hpp"

namespace skybake {
namespace {

ConvergedMultiscatteringSpec small_spec() {
  ConvergedMultiscatteringSpec s;
  s.bruneton.r_size = 8;
  s.bruneton.mu_size = 32;
  s.bruneton.mu_s_size = 8;
  s.bruneton.nu_size = 4;
  s.bruneton.irradiance_width = 32;
  s.bruneton.irradiance_height = 8;
  s.bands = 16;
  return s;
}


class ConvergedEstimators : public testing::TestWithParam<PsiEstimator> {};

// No light but the sun's: an empty shell, and one that only absorbs, over a
// black ground.
TEST_P(ConvergedEstimators, NonScatteringAtmosphereOverABlackGroundIsZero) {
  for (const Atmosphere& medium :
       {fixtures::empty_atmosphere(),
        fixtures::single_component_atmosphere({2e-6, 4e-6, 1e-6}, exponential_profile(8e3))}) {
    Atmosphere atm = medium;
    atm.ground_albedo = glm::dvec3(0.0);
    const Texture t = bake_transmittance_lut(atm, {32, 16, 8}, {});
    MultiscatteringLutSpec table{8, 8, 16, 10};
    ConvergedMultiscatteringSpec spec = small_spec();
    spec.estimator = GetParam();
    const Texture ms = bake_converged_multiscattering_lut(atm, t, table, spec, {});
    for (float v : ms.data) EXPECT_EQ(v, 0.0f);
    EXPECT_EQ(meta_string(ms.metadata, "model"), "converged");
    EXPECT_EQ(meta_string(ms.metadata, "estimator"), psi_estimator_name(GetParam()));
  }
}

TEST_P(ConvergedEstimators, NoMediumOverALitGroundIsTheGroundsMeanRadiance) {
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.ground_albedo = glm::dvec3(0.1, 0.3, 0.8);
  atm.sun_illuminance = glm::dvec3(2.0, 1.0, 0.5);  // Psi is per unit of it
  const Texture t = bake_transmittance_lut(atm, {32, 16, 8}, {});
  ConvergedMultiscatteringSpec spec = small_spec();
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  // No medium: the relative estimator has no direction to weigh (sigma_s = 0)
  // and gives the mean too.
  spec.estimator = GetParam();
  const PsiQuadrature grid = psi_quadrature(spec, field.phases);
  for (double mu_s : {0.3, 0.6, 0.95}) {
    const glm::dvec3 psi =
        compute_converged_multiscattering(atm, t, field, atm.bottom_radius_m, mu_s, grid);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(psi[c], atm.ground_albedo[c] * mu_s / (2.0 * kPi),
                  2e-3 * atm.ground_albedo[c] * mu_s)
          << mu_s << " " << c;
  }
  // The sun below the horizon lights no ground the point sees.
  const glm::dvec3 night =
      compute_converged_multiscattering(atm, t, field, atm.bottom_radius_m, -0.3, grid);
  EXPECT_EQ(night, glm::dvec3(0.0));
}

INSTANTIATE_TEST_SUITE_P(MeanAndRelative, ConvergedEstimators,
                         testing::Values(PsiEstimator::mean, PsiEstimator::relative),
                         [](const testing::TestParamInfo<PsiEstimator>& info) {
                           return std::string(psi_estimator_name(info.param));
                         });

// Mean over many directions of the single scattering arriving at (r, mu_s),
// from compute_single_scattering_direct (no table).
glm::dvec3 mean_single_scattering(const Atmosphere& atm, double r, double mu_s, int n) {
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(n);
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& w : dirs) {
    const double nu = glm::dot(w, sun);
    const SingleScattering s = compute_single_scattering_direct(atm, r, w.z, mu_s, nu, {});
    sum += s.rayleigh * phase_function(PhaseKind::rayleigh, 0.0, nu);
  }
  return sum / double(n);
}

// The field's sun axis stops at converged_mu_s_min, or lower where a cap
// asks (a twilight field, sky_light_source.hpp); its irradiance keeps the
// ground's row alone, equal to a taller table's.
TEST(ConvergedMultiscattering, SunAxisReachesItsCapAndTheGroundRowIsTheTallTables) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {}, {});
  ConvergedMultiscatteringSpec spec = small_spec();
  spec.bruneton.orders = 2;
  spec.bruneton.tolerance = 0.0;
  const ConvergedField plain = compute_converged_field(atm, t, spec, {});
  EXPECT_DOUBLE_EQ(plain.shape.mu_s_min, converged_mu_s_min(atm));
  EXPECT_EQ(plain.ground_irradiance.height, 2);
  BrunetonSpec tall = spec.bruneton;
  tall.mu_s_min = plain.shape.mu_s_min;
  tall.combined_mie_alpha = false;
  tall.irradiance_includes_direct = true;
  const BrunetonTextures b = bake_bruneton(atm, t, tall, {});
  ASSERT_EQ(b.irradiance.height, 8);
  for (int x = 0; x < b.irradiance.width; ++x)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(plain.ground_irradiance.at(x, 0, 0, 0, c), b.irradiance.at(x, 0, 0, 0, c)) << x;
  spec.mu_s_min_cap = std::cos(114.0 * kDeg);
  EXPECT_DOUBLE_EQ(compute_converged_field(atm, t, spec, {}).shape.mu_s_min, spec.mu_s_min_cap);
}

TEST(ConvergedMultiscattering, ThinConservativeSlabIsTheMeanOfSingleScattering) {
  // Vertical optical depth 1e-3 (blue): order 2 carries ~1e-3 of order 1.
  Atmosphere atm = fixtures::uniform_slab_atmosphere({2.5e-9, 5e-9, 1e-8}, glm::dvec3(0.0));
  atm.ground_albedo = glm::dvec3(0.0);
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  ConvergedMultiscatteringSpec spec = small_spec();
  spec.estimator = PsiEstimator::mean;
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature grid = psi_quadrature(spec, field.phases);
  for (double h : {1e3, 50e3}) {
    for (double mu_s : {0.2, 0.8}) {
      const double r = atm.bottom_radius_m + h;
      const glm::dvec3 psi = compute_converged_multiscattering(atm, t, field, r, mu_s, grid);
      const glm::dvec3 expected = mean_single_scattering(atm, r, mu_s, 2048);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(psi[c], expected[c], 0.03 * expected[c]) << h << " " << mu_s << " " << c;
    }
  }
}

// The relative estimator in a thin conservative slab of forward-scattering
// dust (Cornette-Shanks, g = 0.6) over a black ground, from single
// scattering integrated without a table on a Fibonacci set (another
// direction rule than the estimator's grid) and the slab's closed-form
// transmittance: L* is order 1, the source toward v is
// j(v) = int p(v . w) L1(w) dw, single scattering's s1(v) = T_sun p(v . s),
// ground viewers see the point along v with weight
// g(v) = exp(-sigma_t d) / max(|mu|, 0.02) (d the distance to the ground
// along -v, mu = -v_z; 0 where that ray misses the ground), and
//   Psi_rel = sum_v g j / q / sum_v g / q,   q = s1 + j.
constexpr double kDustG = 0.6;
const glm::dvec3 kDustScattering(2.5e-9, 5e-9, 1e-8);

Atmosphere thin_dust_slab() {
  Atmosphere atm = fixtures::empty_atmosphere();
  const double width = atm.top_radius_m - atm.bottom_radius_m;
  atm.components = {fixtures::make_component("dust", kDustScattering, glm::dvec3(0.0),
                                             uniform_profile(0.0, width),
                                             PhaseKind::cornette_shanks, kDustG)};
  atm.ground_albedo = glm::dvec3(0.0);
  return atm;
}

glm::dvec3 ground_viewers_in_slab(const Atmosphere& atm, double r, glm::dvec3 v) {
  const double rb = atm.bottom_radius_m, mu = -v.z;
  // The ray from (0, 0, r) along -v meets the sphere of radius rb where
  // d^2 + 2 r mu d + r^2 - rb^2 = 0.
  const double disc = r * r * mu * mu - (r * r - rb * rb);
  if (mu >= 0.0 || disc < 0.0) return glm::dvec3(0.0);
  const double d = -r * mu - std::sqrt(disc);
  return glm::exp(-kDustScattering * d) / std::max(-mu, 0.02);
}

glm::dvec3 relative_single_scattering(const Atmosphere& atm, const Texture& transmittance,
                                      double r, double mu_s, int n) {
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(n);
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  auto phase = [](double c) { return cornette_shanks_phase(c, kDustG); };
  std::vector<glm::dvec3> light;
  for (const glm::dvec3& w : dirs) {
    const double nu = glm::dot(w, sun);
    light.push_back(compute_single_scattering_direct(atm, r, w.z, mu_s, nu, {}).mie * phase(nu));
  }
  const glm::dvec3 t_sun = lookup_transmittance_to_top(transmittance, atm, r, mu_s);
  glm::dvec3 num(0.0), den(0.0);
  for (size_t i = 0; i < dirs.size(); ++i) {
    glm::dvec3 j(0.0);
    double norm = 0.0;
    for (size_t k = 0; k < dirs.size(); ++k) {
      const double p = phase(glm::dot(dirs[i], dirs[k]));
      j += p * light[k];
      norm += p;
    }
    j /= norm;  // the phase summed to one on the set
    const glm::dvec3 q = t_sun * phase(glm::dot(dirs[i], sun)) + j;
    const glm::dvec3 g = ground_viewers_in_slab(atm, r, dirs[i]);
    num += g * j / q;
    den += g / q;
  }
  return num / den;
}

TEST(ConvergedMultiscattering, ThinConservativeSlabRelativeEstimatorIsOrderOnesFit) {
  const Atmosphere atm = thin_dust_slab();
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  ConvergedMultiscatteringSpec spec = small_spec();
  spec.estimator = PsiEstimator::relative;
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature quadrature = psi_quadrature(spec, field.phases);
  spec.estimator = PsiEstimator::mean;
  const PsiQuadrature mean = psi_quadrature(spec, field.phases);
  for (double h : {1e3, 50e3}) {
    for (double mu_s : {0.2, 0.8}) {
      const double r = atm.bottom_radius_m + h;
      const glm::dvec3 psi = compute_converged_multiscattering(atm, t, field, r, mu_s, quadrature);
      const glm::dvec3 expected = relative_single_scattering(atm, t, r, mu_s, 2048);
      const glm::dvec3 psi_mean = compute_converged_multiscattering(atm, t, field, r, mu_s, mean);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(psi[c], expected[c], 0.02 * expected[c]) << h << " " << mu_s << " " << c;
        // The mean holds the dust's bright forward lobe, which the fit
        // weighs by the whole source there: they are far apart.
        EXPECT_GT(psi_mean[c], 1.15 * expected[c]) << h << " " << mu_s << " " << c;
      }
    }
  }
}

// Both estimators are means of the source over directions with weights >= 0,
// so they lie within its range there; the dust's forward lobe makes that
// range wide.
TEST(ConvergedMultiscattering, EstimatorsLieInTheSourcesRangeOverDirections) {
  const Atmosphere atm = thin_dust_slab();
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  ConvergedMultiscatteringSpec spec = small_spec();
  spec.estimator = PsiEstimator::relative;
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature relative = psi_quadrature(spec, field.phases);
  spec.estimator = PsiEstimator::mean;
  const PsiQuadrature mean = psi_quadrature(spec, field.phases);
  EXPECT_THROW(converged_source_range(atm, t, field, atm.bottom_radius_m, 0.5, mean), Error);
  for (double h : {1e3, 50e3})
    for (double mu_s : {0.2, 0.8}) {
      const double r = atm.bottom_radius_m + h;
      const SourceRange range = converged_source_range(atm, t, field, r, mu_s, relative);
      for (const PsiQuadrature* q : {&relative, &mean}) {
        const glm::dvec3 psi = compute_converged_multiscattering(atm, t, field, r, mu_s, *q);
        for (int c = 0; c < 3; ++c) {
          EXPECT_GT(range.min[c], 0.0);
          EXPECT_GT(range.max[c], 2.0 * range.min[c]) << h << " " << mu_s << " " << c;
          EXPECT_GE(psi[c], range.min[c] * (1 - 1e-9)) << h << " " << mu_s << " " << c;
          EXPECT_LE(psi[c], range.max[c] * (1 + 1e-9)) << h << " " << mu_s << " " << c;
        }
      }
    }
}

TEST(ConvergedMultiscattering, TableReadsBackItsOwnMeanAtTexelCentres) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  MultiscatteringLutSpec table{8, 8, 16, 10};
  table.sun_mapping = SunMapping::terminator;
  const ConvergedMultiscatteringSpec spec = small_spec();
  const Texture ms = bake_converged_multiscattering_lut(atm, t, table, spec, {});
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature grid = psi_quadrature(spec, field.phases);
  const MultiscatteringMapping m = multiscattering_mapping_of(ms);
  ASSERT_EQ(m.sun, SunMapping::terminator);
  for (int y = 0; y < 8; y += 3)
    for (int x = 0; x < 8; ++x) {
      const RadiusSunCosine p =
          r_mu_s_from_multiscattering_uv(atm, {texel_center(x, 8), texel_center(y, 8)}, 8, 8, m);
      const glm::dvec3 direct =
          compute_converged_multiscattering(atm, t, field, p.r, p.mu_s, grid);
      const glm::dvec3 read = lookup_multiscattering(ms, atm, p.r, p.mu_s);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(read[c], direct[c], 1e-6 * direct[c] + 1e-12);
    }
}

// The table's own error (its reads against the mean at the points
// themselves, the bake's error record) with each sun mapping: on Earth the
// terminator mapping brings a 32 x 32 table's largest error under 10 %,
// which the linear axis misses by far (Psi falls by orders of magnitude
// within a texel or two there).
TEST(ConvergedMultiscattering, TerminatorMappingResolvesTheTerminator) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  const ConvergedMultiscatteringSpec spec = small_spec();
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature grid = psi_quadrature(spec, field.phases);
  std::vector<RadiusCosine> points;
  std::vector<glm::dvec3> reference;
  for (size_t i = 0; i < 96; ++i) {
    points.push_back(multiscattering_query(atm, i));
    reference.push_back(compute_converged_multiscattering(atm, t, field, points.back().r,
                                                          points.back().mu, grid));
  }
  double max_rel[2] = {0.0, 0.0};
  for (SunMapping mapping : {SunMapping::linear, SunMapping::terminator}) {
    MultiscatteringLutSpec table{32, 32, 16, 10};
    table.sun_mapping = mapping;
    const Texture ms = converged_multiscattering_table(atm, t, table, spec, field, {});
    ErrorTally tally;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 v = lookup_multiscattering(ms, atm, points[i].r, points[i].mu);
      for (int c = 0; c < 3; ++c) tally.add(v[c], reference[i][c]);
    }
    max_rel[mapping == SunMapping::terminator] = tally.stats().max_rel;
  }
  EXPECT_LT(max_rel[1], 0.10) << "linear: " << max_rel[0];
  EXPECT_GT(max_rel[0], 2.0 * max_rel[1]);
}

}  // namespace
}  // namespace skybake

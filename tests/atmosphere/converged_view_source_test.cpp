// Tests of the converged model's view-dependent source
// (compute_converged_multiscattering_slices, psi_view_nodes.hpp): its
// table's layer 0 is the isotropic table bit for bit; with the mean
// estimator the source carries the scattered power of the isotropic mean
// (energy balance, a conservative dust sky included); in a thin
// conservative slab of g = 0.85 dust, where L* is order 1 and the source
// toward each view is a quadrature of single scattering without a table,
// it follows that source far closer than any isotropic value.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "verify/direct_single_scattering.hpp"

namespace skybake {
namespace {

ConvergedMultiscatteringSpec view_source_spec(PsiEstimator estimator) {
  ConvergedMultiscatteringSpec s;
  s.bruneton.r_size = 8;
  s.bruneton.mu_size = 32;
  s.bruneton.mu_s_size = 8;
  s.bruneton.nu_size = 8;
  s.bruneton.irradiance_width = 32;
  s.bruneton.irradiance_height = 8;
  s.bands = 16;
  s.estimator = estimator;
  s.nu_slices = 8;
  s.zenith_slices = 8;
  return s;
}

// Conservative dust of g = 0.85 filling a Mars-sized shell (no absorption,
// black ground): vertical optical depth `tau`.
Atmosphere dust_shell(double tau) {
  Atmosphere atm = fixtures::empty_atmosphere();
  atm.bottom_radius_m = 3386e3;
  atm.top_radius_m = 3386e3 + 40e3;
  const double width = atm.top_radius_m - atm.bottom_radius_m;
  atm.components = {fixtures::make_component("dust", glm::dvec3(tau / width), glm::dvec3(0.0),
                                             uniform_profile(0.0, width),
                                             PhaseKind::cornette_shanks, 0.85)};
  atm.ground_albedo = glm::dvec3(0.0);
  return atm;
}

// a(nu) + b(mu_v) of `layers` (layer 0 isotropic) toward v under the sun at mu_s.
glm::dvec3 view_source(const std::vector<glm::dvec3>& layers, PsiViewShape shape, double mu_s,
                       glm::dvec3 v) {
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  const std::vector<glm::dvec3> nodes(layers.begin() + 1, layers.end());
  return evaluate_view_nodes(nodes, shape, glm::dot(v, sun), v.z);
}

TEST(ConvergedViewSource, LayerZeroIsTheIsotropicTableBitForBit) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  const MultiscatteringLutSpec table{8, 8, 16, 10};
  ConvergedMultiscatteringSpec spec = view_source_spec(PsiEstimator::relative);
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const Texture view = converged_multiscattering_table(atm, t, table, spec, field, {});
  spec.nu_slices = spec.zenith_slices = 0;
  const Texture isotropic = converged_multiscattering_table(atm, t, table, spec, field, {});
  ASSERT_EQ(view.depth, 17);
  ASSERT_EQ(view.layers, 1);
  ASSERT_EQ(isotropic.depth, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(view.at(x, y, 0, 0, c), isotropic.at(x, y, 0, 0, c));
  const MultiscatteringMapping m = multiscattering_mapping_of(view);
  EXPECT_EQ(m.nu_slices, 8);
  EXPECT_EQ(m.zenith_slices, 8);
  EXPECT_EQ(multiscattering_mapping_of(isotropic).nu_slices, 0);
  EXPECT_EQ(meta_int(view.metadata, "nu_slices"), 8);
  EXPECT_FALSE(isotropic.metadata.count("nu_slices"));
}

// Least squares with the constant in its span keeps the weighted integral:
// with the mean estimator (weights the solid angle) the view source's mean
// over the sphere is the mean of the source it was fitted to, which is the
// mean incident light (each view's phase sums to one on the grid) up to the
// grid's column sums and the ridge's pull.
class ViewSourceEnergy : public testing::TestWithParam<std::string> {};

TEST_P(ViewSourceEnergy, TheMeanEstimatorsViewSourceCarriesTheMeanLight) {
  const Atmosphere atm =
      GetParam() == "earth" ? fixtures::earth_atmosphere() : dust_shell(0.6);
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  const ConvergedMultiscatteringSpec spec = view_source_spec(PsiEstimator::mean);
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature q = psi_quadrature(spec, field.phases);
  for (double h : {0.0, 0.3}) {
    for (double mu_s : {0.1, 0.5, 0.95}) {
      const double r = atm.bottom_radius_m + h * (atm.top_radius_m - atm.bottom_radius_m);
      const std::vector<glm::dvec3> layers = compute_converged_multiscattering_slices(
          atm, t, field, r, mu_s, q, spec.view_shape());
      glm::dvec3 power(0.0);
      double solid_angle = 0.0;
      for (size_t v = 0; v < q.directions.size(); ++v) {
        power += q.solid_angle[v] * view_source(layers, spec.view_shape(), mu_s, q.directions[v]);
        solid_angle += q.solid_angle[v];
      }
      EXPECT_NEAR(solid_angle, 2.0 * kPi, 1e-9);  // the half grid
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(power[c] / solid_angle, layers[0][c], 0.01 * layers[0][c])
            << GetParam() << " h " << h << " mu_s " << mu_s << " channel " << c;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EarthAndConservativeDust, ViewSourceEnergy,
                         testing::Values("earth", "conservative_dust"));

// The source toward v in a thin conservative slab, from order 1 alone
// (compute_single_scattering_direct, no table) on a Fibonacci set, each
// view's phase summed to one on the set.
std::vector<glm::dvec3> thin_slab_source(const Atmosphere& atm, double r, double mu_s,
                                         const std::vector<glm::dvec3>& dirs) {
  const glm::dvec3 sun(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  auto phase = [](double c) { return cornette_shanks_phase(c, 0.85); };
  std::vector<glm::dvec3> light;
  for (const glm::dvec3& w : dirs) {
    const double nu = glm::dot(w, sun);
    light.push_back(compute_single_scattering_direct(atm, r, w.z, mu_s, nu, {}).mie * phase(nu));
  }
  std::vector<glm::dvec3> j;
  for (const glm::dvec3& v : dirs) {
    glm::dvec3 sum(0.0);
    double norm = 0.0;
    for (size_t k = 0; k < dirs.size(); ++k) {
      const double p = phase(glm::dot(v, dirs[k]));
      sum += p * light[k];
      norm += p;
    }
    j.push_back(sum / norm);
  }
  return j;
}

TEST(ConvergedViewSource, ThinDustSlabFollowsTheSourceOfOrderOne) {
  const Atmosphere atm = dust_shell(1e-3);
  const Texture t = bake_transmittance_lut(atm, {64, 32, 20}, {});
  const ConvergedMultiscatteringSpec spec = view_source_spec(PsiEstimator::mean);
  const ConvergedField field = compute_converged_field(atm, t, spec, {});
  const PsiQuadrature q = psi_quadrature(spec, field.phases);
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(1500);
  for (double mu_s : {0.2, 0.8}) {
    const double r = atm.bottom_radius_m + 2e3;
    const std::vector<glm::dvec3> j = thin_slab_source(atm, r, mu_s, dirs);
    const std::vector<glm::dvec3> layers =
        compute_converged_multiscattering_slices(atm, t, field, r, mu_s, q, spec.view_shape());
    // Over the set (equal solid angles), the RMS error against the mean
    // source: what the mean estimator's weights minimise. An isotropic value
    // can do no better than the source's spread about its mean.
    double view_sq = 0.0, spread_sq = 0.0, mean = 0.0;
    for (const glm::dvec3& x : j) mean += x.z / double(j.size());
    for (size_t v = 0; v < dirs.size(); ++v) {
      const double s = view_source(layers, spec.view_shape(), mu_s, dirs[v]).z;
      view_sq += (s - j[v].z) * (s - j[v].z) / double(j.size());
      spread_sq += (mean - j[v].z) * (mean - j[v].z) / double(j.size());
    }
    EXPECT_LT(std::sqrt(view_sq), 0.3 * std::sqrt(spread_sq)) << mu_s;
    EXPECT_GT(std::sqrt(spread_sq), 0.5 * mean) << mu_s;  // the lobe is no detail
    EXPECT_NEAR(layers[0].z, mean, 0.05 * mean) << mu_s;
  }
}

}  // namespace
}  // namespace skybake

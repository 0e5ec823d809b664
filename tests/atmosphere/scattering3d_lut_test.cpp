// Tests of the azimuth-free 3D table and its gathering LUT
// (atmosphere/scattering3d_lut.hpp, gathering_lut.hpp): the mappings against
// Hillaire 2016 Appendix A and their round trips, single scattering against
// a closed form and the 4D integral, the gathering quadrature against closed
// forms, energy, convergence, the bake's outputs and determinism.
#include "atmosphere/scattering3d_lut.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/gathering_lut.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "support/order_progress_checks.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

double mu_horizon(const Atmosphere& atm, double h) {
  const double x = atm.bottom_radius_m / (atm.bottom_radius_m + h);
  return -std::sqrt(std::max(0.0, 1.0 - x * x));
}

Scattering3dSpec small_spec(int orders) {
  Scattering3dSpec spec;
  spec.height_size = 8;
  spec.view_size = 32;
  spec.sun_size = 8;
  spec.orders = orders;
  spec.ray_nodes = 21;
  spec.azimuth_samples = 4;
  spec.gathering_directions = 8;
  return spec;
}

// ---- Mappings -------------------------------------------------------------------

TEST(Scattering3dMapping, AxesRoundTripAtTexelCentres) {
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const double H = atm.top_radius_m - atm.bottom_radius_m;
    for (int n : {8, 32, 128}) {
      for (int i = 0; i < n; ++i) {
        const double u = texel_center(i, n);
        const double h = h_from_scattering3d_u(atm, u, n);
        ASSERT_GE(h, 0.0);
        ASSERT_LE(h, H);
        ASSERT_NEAR(scattering3d_u_from_h(atm, h, n), u, 1e-12);
        const double mu_s = mu_s_from_scattering3d_u(u, n);
        ASSERT_GE(mu_s, kScattering3dMuSMin - 1e-15);
        ASSERT_LE(mu_s, 1.0);
        ASSERT_NEAR(scattering3d_u_from_mu_s(mu_s, n), u, 1e-12);
        for (double f : {0.0, 1e-4, 0.3, 1.0}) {
          bool hits = false;
          const double mu = mu_from_scattering3d_u(atm, f * H, u, n, hits);
          ASSERT_EQ(hits, i < n / 2);
          ASSERT_LE(std::abs(mu), 1.0);
          // The power 0.2 flattens the mapping at the horizon: u error ~ 5
          // (rounding of mu)^(1/5)... only where x = 0 exactly, which is
          // itself the texel centre; elsewhere the round trip is tight.
          ASSERT_NEAR(scattering3d_u_from_mu(atm, f * H, mu, hits, n), u, 1e-9)
              << "n " << n << " i " << i << " h " << f * H;
        }
      }
    }
  }
}

TEST(Scattering3dMapping, MatchesHillaire2016AppendixA) {
  // An independent transcription of Listing 4 (convertSkyParamsToLutCoords)
  // for rays away from the listing's 1e-4 horizon offset and suns above its
  // -0.45 clamp, where the two must agree.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const double Rb = atm.bottom_radius_m, H_atm = atm.top_radius_m - Rb;
  const int res_h = 32, res_v = 128, res_s = 32;
  for (double height : {0.0, 350.0, 8e3, 60e3})
    for (double cos_view : {1.0, 0.5, 0.02, -0.1, -0.6, -1.0})
      for (double cos_sun : {1.0, 0.3, 0.0, -0.2, -0.44}) {
        double nh = std::pow(std::clamp(height, 0.0, H_atm) / H_atm, 0.5);
        const double cos_horizon = -std::sqrt(height * (2 * Rb + height)) / (Rb + height);
        if (std::abs(cos_view - cos_horizon) < 1e-3) continue;
        double nv;
        if (cos_view > cos_horizon) {
          nv = std::pow(std::clamp((cos_view - cos_horizon) / (1 - cos_horizon), 0.0, 1.0), 0.2);
          nv = 0.5 + 0.5 / res_v + nv * (res_v / 2.0 - 1.0) / res_v;
        } else {
          nv = std::pow(std::clamp((cos_horizon - cos_view) / (cos_horizon + 1), 0.0, 1.0), 0.2);
          nv = 0.5 / res_v + nv * (res_v / 2.0 - 1.0) / res_v;
        }
        double ns =
            0.5 * (std::atan(std::max(cos_sun, -0.45) * std::tan(1.26 * 0.75)) / 0.75 + (1 - 0.26));
        nh = (nh * (res_h - 1) + 0.5) / res_h;
        ns = (ns * (res_s - 1) + 0.5) / res_s;
        const glm::dvec3 uvw = scattering3d_uvw_from_h_mu_mu_s(
            atm, {res_h, res_v, res_s}, height, cos_view, cos_sun, cos_view < cos_horizon);
        EXPECT_NEAR(uvw.x, nh, 1e-12);
        EXPECT_NEAR(uvw.y, nv, 1e-12) << height << " " << cos_view;
        EXPECT_NEAR(uvw.z, ns, 1e-12) << cos_sun;
      }
  // The listing's inverse of the sun axis at u = 0 is its lowest sun.
  EXPECT_NEAR(kScattering3dMuSMin, -0.4481, 1e-4);
  EXPECT_EQ(mu_s_from_scattering3d_u(0.5 / 32, 32), kScattering3dMuSMin);
}

TEST(Scattering3dMapping, TexelCentresStayInTheDomain) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Scattering3dShape shape;
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  for (int z = 0; z < shape.sun_size; z += 31)
    for (int y = 0; y < shape.view_size; ++y)
      for (int x = 0; x < shape.height_size; ++x) {
        const Scattering3dParams p = scattering3d_texel_params(atm, shape, x, y, z);
        ASSERT_GE(p.h, 0.0);
        ASSERT_LE(p.h, rt - rb);
        ASSERT_LE(std::abs(p.mu), 1.0);
        const double mu_h = mu_horizon(atm, p.h);
        if (p.ray_hits_ground) {
          ASSERT_LE(p.mu, mu_h + 1e-12);
        } else {
          ASSERT_GE(p.mu, mu_h - 1e-12);
        }
        const double d = distance_to_nearest_boundary(rb, rt, rb + p.h, p.mu, p.ray_hits_ground);
        ASSERT_TRUE(std::isfinite(d));
        ASSERT_GE(d, 0.0);
        // The ends of the view axis: horizon (below), nadir, horizon (above), zenith.
        if (y == 0 || y == shape.view_size / 2) {
          ASSERT_NEAR(p.mu, mu_h, 1e-12);
        }
        if (y == shape.view_size / 2 - 1) {
          ASSERT_NEAR(p.mu, -1.0, 1e-15);
        }
        if (y == shape.view_size - 1) {
          ASSERT_NEAR(p.mu, 1.0, 1e-15);
        }
      }
  EXPECT_EQ(scattering3d_texel_params(atm, shape, 0, 0, 0).h, 0.0);
  EXPECT_NEAR(scattering3d_texel_params(atm, shape, 31, 0, 0).h, rt - rb, 1e-6);
  EXPECT_NEAR(scattering3d_texel_params(atm, shape, 0, 0, 31).mu_s, 1.0, 1e-15);
}

TEST(Scattering3dMapping, RaysRoundTripNextToTheHorizon) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Scattering3dShape shape;
  for (double h : {0.0, 10.0, 2e3, 90e3})
    for (double eps : {1e-8, 1e-5, 1e-3}) {
      for (double mu : {mu_horizon(atm, h) + eps, mu_horizon(atm, h) - eps}) {
        if (mu < -1.0) continue;
        const bool hits = mu < mu_horizon(atm, h);
        const glm::dvec3 uvw = scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, 0.2, hits);
        const Scattering3dParams p = h_mu_mu_s_from_scattering3d_uvw(atm, shape, uvw);
        EXPECT_EQ(p.ray_hits_ground, hits);
        EXPECT_NEAR(p.h, h, 1e-9 * (h + 1));
        // mu = mu_h +- x^5 (1 -+ mu_h): rounding of u (1e-16) gives ~5e-16 / x^4.
        EXPECT_NEAR(p.mu, mu, 1e-12 + 1e-3 * eps) << h << " " << eps;
        EXPECT_NEAR(p.mu_s, 0.2, 1e-12);
      }
    }
}

// ---- Single scattering ------------------------------------------------------------

TEST(ComputeSingleScattering3d, VerticalRayZenithSunInAUniformSlab) {
  // mu = mu_s = 1: every azimuth gives nu = 1, and as in the 4D case
  // T(x, y) T_sun(y) = exp(-sigma_t d) along the whole ray, so
  //   S = E sigma_s d exp(-sigma_t d), d = Rt - r,
  // to the LUT's error toward the sun (measured along the ray).
  const glm::dvec3 sigma_s(3e-6, 6e-6, 1.5e-5), sigma_a(1e-6);
  const Atmosphere atm = fixtures::uniform_slab_atmosphere(sigma_s, sigma_a);
  const Texture lut = bake_transmittance_lut(atm, {64, 256, 40}, BakeContext{});
  for (double h : {0.0, 1e3, 37e3}) {
    const double d = atm.top_radius_m - atm.bottom_radius_m - h;
    const SingleScattering s = compute_single_scattering3d(atm, lut, h, 1.0, 1.0, false, 51, 8);
    const double lut_error =
        fixtures::sun_lut_error_along_ray(lut, atm, atm.bottom_radius_m + h, 1.0, d,
                                          [&](double s) { return (sigma_s + sigma_a) * (d - s); });
    EXPECT_LT(lut_error, 1e-4);
    for (int c = 0; c < 3; ++c) {
      const double exact = sigma_s[c] * d * std::exp(-(sigma_s[c] + sigma_a[c]) * d);
      EXPECT_NEAR(s.rayleigh[c], exact, (lut_error + 1e-9) * exact) << h;
    }
  }
}

TEST(ComputeSingleScattering3d, IsTheAzimuthMeanOfThe4dIntegral) {
  // Averaging over azimuths phi_a = (a + 1/2) pi / N is Gauss-Chebyshev in
  // cos(phi): the mean of the 4D single scattering at those nu.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const double h = 1.5e3, mu = 0.12, mu_s = 0.05;
  const SingleScattering s3 = compute_single_scattering3d(atm, lut, h, mu, mu_s, false, 30, 6);
  SingleScattering mean;
  for (int a = 0; a < 6; ++a) {
    const double nu =
        mu * mu_s + std::sqrt((1 - mu * mu) * (1 - mu_s * mu_s)) * std::cos((a + 0.5) * kPi / 6);
    const SingleScattering s =
        compute_single_scattering(atm, lut, atm.bottom_radius_m + h, mu, mu_s, nu, false, 30);
    mean.rayleigh += s.rayleigh / 6.0;
    mean.mie += s.mie / 6.0;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s3.rayleigh[c], mean.rayleigh[c], 1e-12 * mean.rayleigh[c]);
    EXPECT_NEAR(s3.mie[c], mean.mie[c], 1e-12 * mean.mie[c]);
  }
}

// ---- Gathering ----------------------------------------------------------------------

TEST(Gathering, ConstantTablesGatherTheirSum) {
  // Tables S_R = a, S_M = b everywhere and a black ground:
  //   G = int (p_R(nu) a + p_M(nu) b) d omega = a + b,
  // since each phase integrates to 1 (the weights are normalized to it).
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.ground_albedo = glm::dvec3(0.0);
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 20}, BakeContext{});
  const Scattering3dShape shape{8, 32, 8};
  Texture a(8, 32, 8, 1, {"R", "G", "B"}), b = a;
  for (float& v : a.data) v = 0.5f;
  for (float& v : b.data) v = 0.125f;
  const ScatteringPhases phases = scattering_phases(atm);
  const Scattering3dOrder order{&a, &b, &phases};
  for (double mu_s : {1.0, 0.4, -0.3})
    for (double h : {0.0, 12e3}) {
      const Gathering g = compute_gathering(atm, lut, shape, order, {}, h, mu_s, 8);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.gathered[c], 0.625, 1e-12) << mu_s << " " << h;
    }
  const GatheringPass pass = bake_gathering(atm, lut, shape, order, {}, 8, BakeContext{});
  for (float v : pass.gathering.data) ASSERT_NEAR(v, 0.625f, 1e-6f);
}

TEST(Gathering, GroundIrradianceUnderAConstantRayleighSky) {
  // Rayleigh only, S_R = a, sun at the zenith (nu = cos(theta)):
  //   E = int_hemisphere p_R(cos theta) a cos(theta) d omega
  //     = 2 pi a int_0^1 3 (1 + m^2) / (16 pi) m dm = (3/8)(1/2 + 1/4) a = 9/32 a.
  // The cosine weights come from the fine quadrature (midpoint error ~1e-5).
  const Atmosphere atm = fixtures::uniform_slab_atmosphere(glm::dvec3(1e-5), glm::dvec3(0.0));
  const Texture lut = bake_transmittance_lut(atm, {64, 16, 20}, BakeContext{});
  Texture a(8, 32, 8, 1, {"R", "G", "B"});
  for (float& v : a.data) v = 2.0f;
  const ScatteringPhases phases = scattering_phases(atm);
  ASSERT_FALSE(phases.has_mie);
  const Gathering g = compute_gathering(atm, lut, {8, 32, 8}, {&a, &a, &phases}, {}, 0.0, 1.0, 16);
  EXPECT_NEAR(g.ground.g, 2.0 * 9.0 / 32.0, 1e-4);
}

TEST(Gathering, BakeEqualsThePointwiseGathering) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const Scattering3dSpec spec = small_spec(1);
  const Scattering3dTextures t = bake_scattering3d(atm, lut, spec, BakeContext{});
  const ScatteringPhases phases = scattering_phases(atm);
  Texture rayleigh(8, 32, 8, 1, {"R", "G", "B"});
  for (size_t i = 0; i < rayleigh.texel_count(); ++i)
    for (int c = 0; c < 3; ++c) rayleigh.data[3 * i + c] = t.scattering.data[4 * i + c];
  const Scattering3dOrder order{&rayleigh, &t.mie, &phases};
  const GatheringPass pass = bake_gathering(atm, lut, t.shape, order, {}, 8, BakeContext{});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const double h = h_from_scattering3d_u(atm, texel_center(x, 8), 8);
      const double mu_s = mu_s_from_scattering3d_u(texel_center(y, 8), 8);
      const Gathering g = compute_gathering(atm, lut, t.shape, order, {}, h, mu_s, 8);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(pass.gathering.at(x, y, 0, 0, c), float(g.gathered[c]));
      if (x == 0) {
        ASSERT_EQ(pass.ground_irradiance[y], g.ground);
      }
    }
  // The gathered light is what a point sees of the sky: positive by day.
  EXPECT_GT(pass.gathering.at(0, 7, 0, 0, 2), 0.0f);
  EXPECT_NEAR(lookup_gathering(pass.gathering, atm, 0.0, 1.0).b, pass.gathering.at(0, 7, 0, 0, 2),
              1e-6);
}

// ---- Orders and the bake -------------------------------------------------------------

TEST(BakeScattering3d, EachOrderIsSmallerThanTheLastByTheSlabsOpacity) {
  // Albedo-1 Rayleigh slab, black ground. G_k = sum_bands W S_k with
  // normalized W, so G_k <= max S_k; then
  //   S_{k+1} = int sigma_s T G_k ds <= max S_k (1 - exp(-sigma_s d_max)),
  // d_max = 2 sqrt(Rt^2 - Rb^2). Orders are the differences of bakes with
  // k and k + 1 orders (slack 1e-3 for quadrature and float sums).
  const double sigma = 5e-7;
  Atmosphere atm = fixtures::uniform_slab_atmosphere(glm::dvec3(sigma), glm::dvec3(0.0));
  atm.ground_albedo = glm::dvec3(0.0);
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const double d_max = 2.0 * std::sqrt(atm.top_radius_m * atm.top_radius_m -
                                       atm.bottom_radius_m * atm.bottom_radius_m);
  const double bound = 1.0 - std::exp(-sigma * d_max);
  std::vector<TexelVector> totals;
  for (int orders = 1; orders <= 4; ++orders)
    totals.push_back(
        bake_scattering3d(atm, lut, small_spec(orders), BakeContext{}).scattering.data);
  double previous = *std::max_element(totals[0].begin(), totals[0].end());
  std::vector<double> ratios;
  for (int k = 1; k < 4; ++k) {
    double m = 0.0;
    for (size_t i = 0; i < totals[k].size(); ++i)
      m = std::max(m, double(totals[k][i]) - totals[k - 1][i]);
    ratios.push_back(m / previous);
    EXPECT_LE(m, previous * bound * (1 + 1e-3)) << "order " << k + 1;
    previous = m;
  }
  RecordProperty("order_ratios", fmt::format("{:.3f}", fmt::join(ratios, " ")));
}

TEST(BakeScattering3d, FiftyTimesDenserEarthConverges) {
  const Atmosphere atm = fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 50.0);
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  Scattering3dSpec spec = small_spec(4);
  spec.tolerance = 5e-3;
  spec.max_orders = 400;
  const Scattering3dTextures t = bake_scattering3d(atm, lut, spec, BakeContext{});
  RecordProperty("orders_used", t.orders_used);
  EXPECT_GT(t.orders_used, 10);
  EXPECT_LT(t.orders_used, spec.max_orders);
  EXPECT_LT(t.last_residual, spec.tolerance);
  for (size_t k = t.residuals.size() - 5; k < t.residuals.size(); ++k)
    EXPECT_LT(t.residuals[k], t.residuals[k - 1]);
  for (const Texture* tex : {&t.scattering, &t.mie, &t.gathering_sum})
    for (float v : tex->data) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
    }
}

TEST(BakeScattering3d, GeometricTailApproachesTheConvergedTableFromBelow) {
  // As the 4D test (scattering_orders_test.cpp): 20x Earth, where the orders
  // decay slowly. Stopped early (tolerance 0.05), the tables without the
  // tail miss the later orders; the tail (f DeltaS_N, f G_{N-1} for the
  // gathering sum, header) must bring every channel of the table, its Mie
  // texture and the gathering sum closer to the bake iterated to 1e-4
  // without a tail, and, the tail being an underestimate, never above it
  // (0.5% slack for the reference's own unconverged remainder).
  const Atmosphere atm = fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 20.0);
  const Texture lut = bake_transmittance_lut(atm, {128, 32, 40}, BakeContext{});
  Scattering3dSpec spec = small_spec(4);
  spec.combined_mie_alpha = false;
  spec.max_orders = 400;
  auto total = [](const Texture& t) {
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < t.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) sum[c] += t.data[3 * i + c];
    return sum;
  };
  spec.tolerance = 1e-4;
  spec.geometric_tail = false;
  const Scattering3dTextures reference = bake_scattering3d(atm, lut, spec, BakeContext{});
  spec.tolerance = 0.05;
  const Scattering3dTextures plain = bake_scattering3d(atm, lut, spec, BakeContext{});
  spec.geometric_tail = true;
  const Scattering3dTextures tail = bake_scattering3d(atm, lut, spec, BakeContext{});
  EXPECT_EQ(plain.orders_used, tail.orders_used);
  EXPECT_GE(tail.orders_used, 3) << "no ratio of two multiple orders to extrapolate";
  EXPECT_EQ(plain.tail_factor, glm::dvec3(0.0));
  EXPECT_EQ(meta_double3(reference.scattering.metadata, "geometric_tail"), glm::dvec3(0.0));
  EXPECT_EQ(meta_double3(tail.gathering_sum.metadata, "geometric_tail"), tail.tail_factor);
  RecordProperty("orders",
                 fmt::format("{} (reference {})", tail.orders_used, reference.orders_used));
  RecordProperty("tail_factor", fmt::format("{:.3f} {:.3f} {:.3f}", tail.tail_factor.x,
                                            tail.tail_factor.y, tail.tail_factor.z));
  struct Table {
    const char* name;
    const Texture Scattering3dTextures::*texture;
  };
  for (const Table table : {Table{"scattering", &Scattering3dTextures::scattering},
                            Table{"mie", &Scattering3dTextures::mie},
                            Table{"gathering_sum", &Scattering3dTextures::gathering_sum}}) {
    const glm::dvec3 ref = total(reference.*table.texture), without = total(plain.*table.texture),
                     with = total(tail.*table.texture);
    RecordProperty(std::string(table.name) + "_blue_without_with",
                   fmt::format("{:.4f} {:.4f}", without.b / ref.b, with.b / ref.b));
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(tail.tail_factor[c], 0.0) << c;
      EXPECT_LT(std::abs(with[c] - ref[c]), std::abs(without[c] - ref[c])) << table.name << c;
      EXPECT_LE(with[c], 1.005 * ref[c]) << table.name << c;
    }
  }
}

TEST(BakeScattering3d, ExtremeMediaStayFiniteAndNonNegative) {
  Atmosphere sharp = fixtures::earth_atmosphere();
  sharp.components[1].g = 0.999;
  for (const Atmosphere& atm : {fixtures::tiny_planet_atmosphere(), sharp}) {
    const Texture lut = bake_transmittance_lut(atm, {64, 16, 20}, BakeContext{});
    const Scattering3dTextures t = bake_scattering3d(atm, lut, small_spec(3), BakeContext{});
    for (const Texture* tex : {&t.scattering, &t.mie, &t.gathering_sum})
      for (float v : tex->data) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
      }
  }
}

TEST(BakeScattering3d, ShapesChannelsMetadataAndLayouts) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  Scattering3dSpec spec = small_spec(3);
  const Scattering3dTextures t = bake_scattering3d(atm, lut, spec, BakeContext{});
  EXPECT_EQ(t.scattering.width, 8);
  EXPECT_EQ(t.scattering.height, 32);
  EXPECT_EQ(t.scattering.depth, 8);
  EXPECT_EQ(t.scattering.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(t.gathering_sum.width, 8);
  EXPECT_EQ(t.gathering_sum.height, 8);
  EXPECT_EQ(t.orders_used, 3);
  EXPECT_EQ(t.residuals.size(), 2u);
  for (size_t i = 0; i < t.mie.texel_count(); ++i)
    ASSERT_EQ(t.scattering.data[4 * i + 3], t.mie.data[3 * i]);
  EXPECT_EQ(meta_string(t.scattering.metadata, "parameterization"), "azimuth_free_3d_scattering");
  EXPECT_EQ(meta_int(t.scattering.metadata, "orders"), 3);
  EXPECT_EQ(meta_double(t.scattering.metadata, "last_residual"), t.last_residual);
  EXPECT_EQ(meta_int(t.gathering_sum.metadata, "orders"), 3);
  EXPECT_FALSE(meta_string(t.scattering.metadata, "mapping").empty());

  spec.combined_mie_alpha = false;
  const Scattering3dTextures u = bake_scattering3d(atm, lut, spec, BakeContext{});
  EXPECT_EQ(u.scattering.channels, (std::vector<std::string>{"R", "G", "B"}));
  // The runtime read: at a texel centre, p_R S_R + p_M S_M; eq. 19 from the
  // alpha channel stays close (exact only when Mie follows Rayleigh).
  const ScatteringPhases phases = scattering_phases(atm);
  const Scattering3dParams p = scattering3d_texel_params(atm, t.shape, 2, 25, 6);
  const glm::dvec3 L = lookup_scattering3d(u.scattering, u.mie, u.shape, atm, p.h, p.mu, p.mu_s,
                                           0.3, p.ray_hits_ground);
  for (int c = 0; c < 3; ++c) {
    const double expected = phases.rayleigh(0.3) * u.scattering.at(2, 25, 6, 0, c) +
                            phases.mie(0.3) * u.mie.at(2, 25, 6, 0, c);
    EXPECT_NEAR(L[c], expected, 1e-6 * expected);
  }
  const glm::dvec3 from_alpha = lookup_scattering3d(t.scattering, Texture{}, t.shape, atm, p.h,
                                                    p.mu, p.mu_s, 0.3, p.ray_hits_ground);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(from_alpha[c], L[c], 0.2 * L[c]);
  // Physics: a blue zenith for a high sun.
  const glm::dvec3 zenith =
      lookup_scattering3d(u.scattering, u.mie, u.shape, atm, 0.0, 1.0, 0.8, 0.8, false);
  EXPECT_GT(zenith.b, zenith.g);
  EXPECT_GT(zenith.g, zenith.r);
}

TEST(BakeScattering3d, SameDataForOneAndTwoThreads) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  Scattering3dTextures one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_scattering3d(atm, lut, small_spec(3), BakeContext{});
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_scattering3d(atm, lut, small_spec(3), BakeContext{});
  }
  EXPECT_TRUE(one.scattering.data == two.scattering.data);
  EXPECT_TRUE(one.gathering_sum.data == two.gathering_sum.data);
}

TEST(BakeScattering3d, ProgressFollowsTheOrdersAToleranceTakes) {
  // As the 4D test (scattering_orders_test.cpp): never decreasing, 1 only
  // at the end, past half when the last order starts. One thread: the
  // reports arrive in order.
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const Atmosphere atm = fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 50.0);
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  Scattering3dSpec spec = small_spec(4);
  spec.tolerance = 5e-3;
  spec.max_orders = 400;
  std::vector<double> seen;
  BakeContext ctx;
  ctx.on_progress = [&](double f) { seen.push_back(f); };
  const Scattering3dTextures t = bake_scattering3d(atm, lut, spec, ctx);
  ASSERT_GT(t.orders_used, 10);
  // Each order k >= 2 reports once per (h, mu_s) texel of its gathering and
  // once per (h, mu) row of its table; the bake then reports 1.
  const size_t per_order = size_t(spec.height_size) * (spec.sun_size + spec.view_size);
  fixtures::expect_progress_follows_the_orders(seen, per_order, t.orders_used);
}

TEST(BakeScattering3d, RejectsBadSpecs) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {16, 4, 5}, BakeContext{});
  Scattering3dSpec spec = small_spec(4);
  spec.view_size = 33;
  try {
    bake_scattering3d(atm, lut, spec, BakeContext{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "scattering3d: expected height >= 2, view even >= 4, sun >= 2 texels, got 8 x 33 x 8");
  }
  spec = small_spec(4);
  spec.gathering_directions = 5;
  EXPECT_THROW(bake_scattering3d(atm, lut, spec, BakeContext{}), Error);
}

}  // namespace
}  // namespace skybake

// Tests of the transmittance LUT (atmosphere/transmittance_lut.hpp): the
// (r, mu) <-> uv mapping round trips, invariants of T, the bake and the
// lookups. The optical depth's quadrature is tested in
// optical_depth_test.cpp.
#include "atmosphere/transmittance_lut.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/geometry.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"
#include "support/transmittance_rays.hpp"

namespace skybake {
namespace {

// ---- Mapping ----------------------------------------------------------------

TEST(TransmittanceMapping, RMuRoundTrip) {
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    for (const fixtures::Ray& ray : fixtures::domain_rays(atm)) {
      const glm::dvec2 uv = transmittance_uv_from_r_mu(atm, ray.r, ray.mu, 256, 64);
      double r = 0.0, mu = 0.0;
      r_mu_from_transmittance_uv(atm, uv, 256, 64, r, mu);
      EXPECT_NEAR(r, ray.r, 1e-9 * ray.r) << "r " << ray.r << " mu " << ray.mu;
      EXPECT_NEAR(mu, ray.mu, 1e-9) << "r " << ray.r << " mu " << ray.mu;
    }
  }
}

TEST(TransmittanceMapping, UvRoundTripAtEveryTexelCentre) {
  const int W = 256, H = 64;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const glm::dvec2 uv(texel_center(x, W), texel_center(y, H));
        double r = 0.0, mu = 0.0;
        r_mu_from_transmittance_uv(atm, uv, W, H, r, mu);
        const glm::dvec2 back = transmittance_uv_from_r_mu(atm, r, mu, W, H);
        ASSERT_NEAR(back.x, uv.x, 1e-9 / W) << x << " " << y;
        ASSERT_NEAR(back.y, uv.y, 1e-9 / H) << x << " " << y;
      }
  }
}

TEST(TransmittanceMapping, TexelCentresStayInTheDomain) {
  // Sampling at i / N instead of texel centres puts the first texel before
  // x = 0: d < d_min, which is d < 0 at the top (docs/reference.md "Pitfalls").
  const int W = 256, H = 64;
  const Atmosphere atm = fixtures::earth_atmosphere();
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      double r = 0.0, mu = 0.0;
      r_mu_from_transmittance_uv(atm, {texel_center(x, W), texel_center(y, H)}, W, H, r, mu);
      ASSERT_GE(r, rb);
      ASSERT_LE(r, rt);
      ASSERT_LE(std::abs(mu), 1.0);
      ASSERT_GE(mu, fixtures::mu_horizon(atm, r) - 1e-12)
          << "texel " << x << " " << y << " below the horizon";
      const double d = distance_to_top_boundary(rt, r, mu);
      ASSERT_TRUE(std::isfinite(d));
      ASSERT_GE(d, 0.0);
      // The first column is the zenith, the last one the horizon.
      if (x == 0) {
        ASSERT_NEAR(mu, 1.0, 1e-12) << y;
      }
      if (x == W - 1) {
        ASSERT_NEAR(mu, fixtures::mu_horizon(atm, r), 1e-9) << y;
      }
    }
  // And the boundary rays land on the first and last texel centres, not on
  // the texture's edges.
  const glm::dvec2 ground_zenith = transmittance_uv_from_r_mu(atm, rb, 1.0, W, H);
  const glm::dvec2 top_horizon = transmittance_uv_from_r_mu(atm, rt, fixtures::mu_horizon(atm, rt), W, H);
  EXPECT_NEAR(ground_zenith.x, 0.5 / W, 1e-15);
  EXPECT_NEAR(ground_zenith.y, 0.5 / H, 1e-15);
  EXPECT_NEAR(top_horizon.x, 1.0 - 0.5 / W, 1e-12);
  EXPECT_NEAR(top_horizon.y, 1.0 - 0.5 / H, 1e-12);
}

TEST(TransmittanceMapping, TopBoundaryUpwardRaysMapToTheZenithColumn) {
  // At r = Rt every ray with mu >= 0 leaves at once (d = 0): the mapping
  // cannot tell them apart, the inverse returns mu = 1, and T = 1 for all.
  const Atmosphere atm = fixtures::earth_atmosphere();
  for (double mu : {0.0, 0.3, 1.0}) {
    const glm::dvec2 uv = transmittance_uv_from_r_mu(atm, atm.top_radius_m, mu, 256, 64);
    EXPECT_NEAR(uv.x, 0.5 / 256, 1e-15);
    double r = 0.0, mu_back = 0.0;
    r_mu_from_transmittance_uv(atm, uv, 256, 64, r, mu_back);
    EXPECT_NEAR(mu_back, 1.0, 1e-12);
    EXPECT_EQ(compute_transmittance_to_top(atm, atm.top_radius_m, mu, 40), glm::dvec3(1.0));
  }
}

TEST(TransmittanceMapping, BelowTheHorizonClampsToTheHorizonColumn) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const double r = atm.bottom_radius_m + 5e3;
  const glm::dvec2 below = transmittance_uv_from_r_mu(atm, r, -0.5, 256, 64);
  const glm::dvec2 horizon = transmittance_uv_from_r_mu(atm, r, fixtures::mu_horizon(atm, r), 256, 64);
  EXPECT_NEAR(below.x, 1.0 - 0.5 / 256, 1e-15);
  EXPECT_NEAR(below.x, horizon.x, 1e-9);
}
// ---- Invariants -------------------------------------------------------------

TEST(ComputeTransmittance, EmptyAtmosphereIsExactlyOne) {
  const Atmosphere atm = fixtures::empty_atmosphere();
  for (const fixtures::Ray& ray : fixtures::domain_rays(atm))
    EXPECT_EQ(compute_transmittance_to_top(atm, ray.r, ray.mu, 40), glm::dvec3(1.0));
  const Texture lut = bake_transmittance_lut(atm, {32, 8, 40}, BakeContext{});
  for (float v : lut.data) ASSERT_EQ(v, 1.0f);
}

TEST(ComputeTransmittance, ManyRaysAreTheOneRayValuesBitForBit) {
  // The error record's batch (set-up shared per task) against one call per
  // ray, both rules, on a medium with kinks (ozone) and one with perigee cuts.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    std::vector<glm::dvec2> rays;
    for (const fixtures::Ray& ray : fixtures::domain_rays(atm)) rays.push_back({ray.r, ray.mu});
    ASSERT_GT(rays.size(), 16u);
    for (SegmentRule rule : {SegmentRule::gauss3, SegmentRule::gauss8}) {
      const std::vector<glm::dvec3> many = compute_transmittances_to_top(atm, rays, 24, rule);
      ASSERT_EQ(many.size(), rays.size());
      for (size_t i = 0; i < rays.size(); ++i)
        ASSERT_EQ(many[i], compute_transmittance_to_top(atm, rays[i].x, rays[i].y, 24, rule)) << i;
    }
  }
}

TEST(ComputeTransmittance, ManyRaysWithBlockExponentialsWithinRounding) {
  // The error record's reference takes the nodes' exponentials in blocks
  // (exp_block, within 3e-16 relative of std::exp): the optical depth moves
  // by rounding, T = exp(-tau) by about tau times that.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    std::vector<glm::dvec2> rays;
    for (const fixtures::Ray& ray : fixtures::domain_rays(atm)) rays.push_back({ray.r, ray.mu});
    const std::vector<glm::dvec3> libm = compute_transmittances_to_top(atm, rays, 24);
    const std::vector<glm::dvec3> block =
        compute_transmittances_to_top(atm, rays, 24, SegmentRule::gauss3, NodeExp::block);
    for (size_t i = 0; i < rays.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double tau = -std::log(libm[i][c]);
        ASSERT_NEAR(block[i][c], libm[i][c], 2e-15 * (1.0 + tau) * libm[i][c] + 1e-300) << i;
      }
  }
}

TEST(ComputeTransmittance, MonotoneInMuAndR) {
  // A lower ray crosses more air at every altitude: T does not increase as
  // mu goes from the zenith to the horizon. Going up along the vertical
  // leaves less air above: T does not decrease with r.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb, rb + 0.02 * (rt - rb), rb + 0.3 * (rt - rb)}) {
      const double mu_h = fixtures::mu_horizon(atm, r);
      glm::dvec3 previous = compute_transmittance_to_top(atm, r, 1.0, 40);
      for (int i = 1; i <= 400; ++i) {
        const double mu = 1.0 - (1.0 - mu_h) * i / 400.0;
        const glm::dvec3 T = compute_transmittance_to_top(atm, r, mu, 40);
        for (int c = 0; c < 3; ++c) ASSERT_LE(T[c], previous[c]) << "r " << r << " mu " << mu;
        previous = T;
      }
    }
    glm::dvec3 previous(0.0);
    for (int i = 0; i <= 100; ++i) {
      const glm::dvec3 T = compute_transmittance_to_top(atm, rb + (rt - rb) * i / 100.0, 1.0, 40);
      for (int c = 0; c < 3; ++c) ASSERT_GE(T[c], previous[c]) << i;
      previous = T;
    }
  }
}

TEST(BakeTransmittanceLut, InTheUnitIntervalAndMonotoneAlongRows) {
  // Earth, Earth 100x denser (T underflows to 0 near the horizon, never NaN)
  // and the tiny planet. Along a row x grows with the distance d, i.e. mu
  // goes down: T does not increase (float rounding is monotone too).
  for (const Atmosphere& atm :
       {fixtures::earth_atmosphere(), fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 100.0),
        fixtures::tiny_planet_atmosphere()}) {
    const Texture lut = bake_transmittance_lut(atm, {64, 16, 40}, BakeContext{});
    for (float v : lut.data) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
    }
    for (int y = 0; y < lut.height; ++y)
      for (int x = 1; x < lut.width; ++x)
        for (int c = 0; c < 3; ++c) ASSERT_LE(lut.at(x, y, 0, 0, c), lut.at(x - 1, y, 0, 0, c));
  }
}

// ---- Bake -------------------------------------------------------------------

// Earth baked once at the default size for the tests below.
class EarthLut : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    atm_ = new Atmosphere(fixtures::earth_atmosphere());
    lut_ = new Texture(bake_transmittance_lut(*atm_, TransmittanceLutSpec{}, BakeContext{}));
  }
  static void TearDownTestSuite() {
    delete lut_;
    delete atm_;
  }
  static const Atmosphere* atm_;
  static const Texture* lut_;
};
const Atmosphere* EarthLut::atm_ = nullptr;
const Texture* EarthLut::lut_ = nullptr;

TEST_F(EarthLut, ShapeChannelsAndMetadata) {
  const Texture& lut = *lut_;
  EXPECT_EQ(lut.width, 256);
  EXPECT_EQ(lut.height, 64);
  EXPECT_EQ(lut.depth, 1);
  EXPECT_EQ(lut.layers, 1);
  EXPECT_EQ(lut.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(lut.data.size(), size_t(256 * 64 * 3));
  const Metadata& m = lut.metadata;
  EXPECT_EQ(meta_string(m, "parameterization"), "bruneton_transmittance");
  EXPECT_EQ(meta_double(m, "bottom_radius_m"), atm_->bottom_radius_m);
  EXPECT_EQ(meta_double(m, "top_radius_m"), atm_->top_radius_m);
  EXPECT_NEAR(meta_double(m, "horizon_distance_m"), std::sqrt(6460e3 * 6460e3 - 6360e3 * 6360e3),
              1e-6);
  EXPECT_EQ(meta_int(m, "width"), 256);
  EXPECT_EQ(meta_int(m, "height"), 64);
  EXPECT_EQ(meta_int(m, "integration_steps"), 6);
  for (const char* key : {"quantity", "texel_centers", "mapping", "inverse_mapping", "domain"})
    EXPECT_FALSE(meta_string(m, key).empty()) << key;
  EXPECT_NE(meta_string(m, "mapping").find("x_mu = (d - d_min)/(d_max - d_min)"), std::string::npos);
}

TEST_F(EarthLut, TexelsHoldTheTransmittanceOfTheirCentre) {
  const Texture& lut = *lut_;
  for (int y = 0; y < lut.height; y += 7)
    for (int x = 0; x < lut.width; x += 5) {
      double r = 0.0, mu = 0.0;
      r_mu_from_transmittance_uv(*atm_, {texel_center(x, 256), texel_center(y, 64)}, 256, 64, r,
                                 mu);
      const glm::dvec3 T = compute_transmittance_to_top(*atm_, r, mu, 6, SegmentRule::gauss8);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(lut.at(x, y, 0, 0, c), float(T[c])) << x << " " << y;
    }
  // Sanity against physics: straight up from the ground Earth lets most
  // light through, toward the horizon blue is almost gone.
  EXPECT_GT(lut.at(0, 0, 0, 0, 0), 0.9f);
  EXPECT_LT(lut.at(255, 0, 0, 0, 2), 1e-3f);
}

TEST(BakeTransmittanceLut, SameDataForOneAndTwoThreads) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  TexelVector one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{}).data;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{}).data;
  }
  ASSERT_EQ(one.size(), two.size());
  EXPECT_TRUE(one == two) << "texels differ between 1 and 2 threads";
}

TEST(BakeTransmittanceLut, ReportsProgressUpToOne) {
  std::mutex mutex;
  double last = 0.0;
  int calls = 0;
  BakeContext ctx;
  ctx.on_progress = [&](double f) {
    std::lock_guard<std::mutex> lock(mutex);
    last = std::max(last, f);
    ++calls;
  };
  bake_transmittance_lut(fixtures::empty_atmosphere(), {16, 8, 4}, ctx);
  EXPECT_EQ(calls, 8);  // one per row
  EXPECT_EQ(last, 1.0);
}

TEST(BakeTransmittanceLut, RefusesADegenerateSize) {
  EXPECT_THROW(bake_transmittance_lut(fixtures::empty_atmosphere(), {1, 64, 40}, BakeContext{}),
               Error);
  EXPECT_THROW(bake_transmittance_lut(fixtures::empty_atmosphere(), {256, 64, 0}, BakeContext{}),
               Error);
}

// ---- Lookups ----------------------------------------------------------------

TEST_F(EarthLut, LookupAtTexelCentresIsTheStoredTexel) {
  const Texture& lut = *lut_;
  for (int y = 0; y < lut.height; ++y)
    for (int x = 0; x < lut.width; ++x) {
      double r = 0.0, mu = 0.0;
      r_mu_from_transmittance_uv(*atm_, {texel_center(x, 256), texel_center(y, 64)}, 256, 64, r,
                                 mu);
      const glm::dvec3 T = lookup_transmittance_to_top(lut, *atm_, r, mu);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(T[c], lut.at(x, y, 0, 0, c), 1e-7) << x << " " << y;
    }
}

TEST_F(EarthLut, LookupToTopInterpolatesTheIntegral) {
  // Between texel centres the bilinear read stays close to the integral. The
  // error is the table's: along v the altitude is quadratic in rho (h ~
  // rho^2 / 2 Rb), so even a T linear in h is curved in v, by about
  // (H / 63)^2 / 8 |dT/dh| / Rb ~ 1e-4 near the ground; the worst case,
  // ~2e-3, is near the horizon at 40 km, where the ozone tent ends between
  // two rows.
  double max_error = 0.0, sum_error = 0.0;
  int count = 0;
  const double rb = atm_->bottom_radius_m;
  for (double h : {0.0, 500.0, 3e3, 12e3, 40e3, 90e3})
    for (double mu : {1.0, 0.8, 0.4, 0.15, 0.05, 0.01}) {
      const glm::dvec3 T = lookup_transmittance_to_top(*lut_, *atm_, rb + h, mu);
      const glm::dvec3 exact = compute_transmittance_to_top(*atm_, rb + h, mu, 200);
      for (int c = 0; c < 3; ++c) {
        max_error = std::max(max_error, std::abs(T[c] - exact[c]));
        sum_error += std::abs(T[c] - exact[c]);
        ++count;
      }
    }
  EXPECT_LT(max_error, 3e-3);
  EXPECT_LT(sum_error / count, 3e-4);
}

TEST_F(EarthLut, LookupBetweenTwoPointsIsTheSegmentTransmittance) {
  // T(p, q) = exp(-tau of the segment), tau integrated directly. Both kinds
  // of rays: missing the ground (ratio of two lookups) and hitting it (ratio
  // of two reversed, upward lookups). Tolerances are the table's, not the
  // quadrature's: a ratio of two interpolated transmittances carries the sum
  // of their relative errors, which is largest for low, grazing rays (two
  // small T near the horizon a few rows above the ground): ~1e-3 for rays
  // that miss the ground, ~1e-2 for a ray 100 m up that dips to the ground at
  // mu = -0.02; 1e-4 typically.
  const double rb = atm_->bottom_radius_m;
  int hitting = 0, count = 0;
  double sum_error = 0.0;
  for (double h : {100.0, 2e3, 10e3, 30e3})
    for (double mu : {1.0, 0.5, 0.2, 0.05, -0.02, -0.1, -0.4, -1.0})
      for (double fraction : {0.05, 0.3, 1.0}) {
        const double r = rb + h;
        const bool hits = ray_intersects_ground(rb, r, mu);
        hitting += hits;
        const double d =
            fraction * distance_to_nearest_boundary(rb, atm_->top_radius_m, r, mu, hits);
        const glm::dvec3 exact = glm::exp(-compute_optical_depth(*atm_, r, mu, d, 200));
        const glm::dvec3 T = lookup_transmittance(*lut_, *atm_, r, mu, d, hits);
        for (int c = 0; c < 3; ++c) {
          ASSERT_GE(T[c], 0.0);
          ASSERT_LE(T[c], 1.0);
          EXPECT_NEAR(T[c], exact[c], hits ? 1.5e-2 : 2e-3)
              << "h " << h << " mu " << mu << " d " << d << " c " << c;
          sum_error += std::abs(T[c] - exact[c]);
          ++count;
        }
      }
  EXPECT_GT(hitting, 10);
  EXPECT_LT(sum_error / count, 5e-4);
}

TEST_F(EarthLut, LookupOfTheWholeRayIsTheLookupToTop) {
  // From p to the top boundary the second factor is T(Rt, mu_d >= 0) = 1.
  const double r = atm_->bottom_radius_m + 3e3;
  for (double mu : {1.0, 0.3, 0.01}) {
    const double d = distance_to_top_boundary(atm_->top_radius_m, r, mu);
    const glm::dvec3 whole = lookup_transmittance(*lut_, *atm_, r, mu, d, false);
    const glm::dvec3 to_top = lookup_transmittance_to_top(*lut_, *atm_, r, mu);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(whole[c], to_top[c], 1e-6) << mu;
  }
}

TEST_F(EarthLut, LookupOfAnEmptySegmentIsOne) {
  const double r = atm_->bottom_radius_m + 1e3;
  for (double mu : {0.7, -0.5}) {
    const glm::dvec3 T = lookup_transmittance(*lut_, *atm_, r, mu, 0.0,
                                              ray_intersects_ground(atm_->bottom_radius_m, r, mu));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(T[c], 1.0, 1e-6);
  }
}

// The per-radius lookup (transmittance_at_radius, then many cosines) is the
// lookup: the same value bit for bit, radii outside the shell (clamped) and
// cosines below the horizon or outside [-1, 1] included.
TEST_F(EarthLut, LookupAtARadiusIsTheLookupBitForBit) {
  const double rb = atm_->bottom_radius_m, rt = atm_->top_radius_m;
  for (double r : {rb - 10.0, rb, rb + 1.0, rb + 3e3, rb + 47.3e3, rt - 1.0, rt, rt + 5e3}) {
    const TransmittanceAtRadius at = transmittance_at_radius(*lut_, *atm_, r);
    for (double mu : {-1.5, -1.0, -0.3, -0.12, -0.05, 0.0, 1e-4, 0.07, 0.4, 0.999, 1.0, 2.0}) {
      const glm::dvec3 a = lookup_transmittance_to_top(*lut_, *atm_, r, mu);
      const glm::dvec3 b = lookup_transmittance_to_top(*lut_, at, mu);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]) << "r " << r << " mu " << mu;
    }
  }
}

}  // namespace
}  // namespace skybake

// Tests of the 4D scattering table's shared machinery and single scattering
// (atmosphere/scattering_lut.hpp): the (r, mu, mu_s, nu) <-> uvwz mapping
// round trips, texel centres inside the domain, the ray quadrature, the
// transmittance reader, single scattering against closed forms, the bake
// and the runtime read (Mie in alpha, Bodare & Sandberg eq. 19).
#include "atmosphere/scattering_lut.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

double mu_horizon(const Atmosphere& atm, double r) {
  const double x = atm.bottom_radius_m / r;
  return -std::sqrt(std::max(0.0, 1.0 - x * x));
}

const ScatteringShape kSmall{16, 64, 16, 4, kBrunetonMuSMin};

// ---- Mapping ----------------------------------------------------------------

TEST(ScatteringMapping, UvwzRoundTripAtEveryTexelCentre) {
  // uvwz of a texel centre -> (r, mu, mu_s, nu) -> uvwz is the identity,
  // except on the two degenerate rows of the header: at r = Rb every ground
  // ray has d = 0 (they all come back as the nadir texel's coordinate), and
  // at r = Rt the zenith texel stands for every upward ray.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    for (double mu_s_min : {kBrunetonMuSMin, std::cos(120.0 * kPi / 180.0)}) {
      ScatteringShape shape = kSmall;
      shape.mu_s_min = mu_s_min;
      for (int z = 0; z < shape.r_size; ++z)
        for (int y = 0; y < shape.mu_size; ++y)
          for (int l = 0; l < shape.mu_s_size; ++l)
            for (int m = 0; m < shape.nu_size; ++m) {
              const glm::dvec4 uvwz(double(m) / (shape.nu_size - 1),
                                    texel_center(l, shape.mu_s_size),
                                    texel_center(y, shape.mu_size), texel_center(z, shape.r_size));
              const ScatteringParams p = r_mu_mu_s_nu_from_scattering_uvwz(atm, shape, uvwz);
              ASSERT_EQ(p.ray_hits_ground, y < shape.mu_size / 2);
              const glm::dvec4 back = scattering_uvwz_from_r_mu_mu_s_nu(
                  atm, shape, p.r, p.mu, p.mu_s, p.nu, p.ray_hits_ground);
              ASSERT_NEAR(back.x, uvwz.x, 1e-12);
              ASSERT_NEAR(back.y, uvwz.y, 1e-9) << l;
              ASSERT_NEAR(back.w, uvwz.w, 1e-9) << z;
              if (z == 0 && p.ray_hits_ground) {
                ASSERT_NEAR(back.z, 0.5 - 0.5 / shape.mu_size, 1e-12);  // the nadir texel
                continue;
              }
              // Next to the horizon d depends on mu through sqrt(mu^2 - mu_h^2):
              // rounding of mu (1e-16) comes back as ~1e-7 in u (1e-5 texel).
              ASSERT_NEAR(back.z, uvwz.z, 1e-6) << "r " << z << " mu " << y;
            }
    }
  }
}

TEST(ScatteringMapping, RaysRoundTripNextToTheHorizon) {
  // Rays just above and just below the horizon, at every altitude: the
  // mapping separates the two halves and inverts back to the same ray.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double f : {1e-4, 0.01, 0.1, 0.5, 0.9, 1.0}) {
      const double r = rb + f * (rt - rb), mu_h = mu_horizon(atm, r);
      for (double eps : {1e-7, 1e-5, 1e-3, 0.05}) {
        for (double mu : {mu_h + eps, mu_h - eps}) {
          if (mu < -1.0) continue;
          const bool hits = ray_intersects_ground(rb, r, mu);
          ASSERT_EQ(hits, mu < mu_h);
          for (double mu_s : {kBrunetonMuSMin, 0.0, 0.3, 1.0}) {
            const double nu = mu * mu_s;  // always geometric
            const glm::dvec4 uvwz =
                scattering_uvwz_from_r_mu_mu_s_nu(atm, kSmall, r, mu, mu_s, nu, hits);
            EXPECT_EQ(uvwz.z < 0.5, hits);
            const ScatteringParams p = r_mu_mu_s_nu_from_scattering_uvwz(atm, kSmall, uvwz);
            EXPECT_NEAR(p.r, r, 1e-9 * r);
            // d is the mapped quantity; near the horizon dmu = dd / (r sin) and
            // rounding of d (1e-16 relative) stays far below eps.
            EXPECT_NEAR(p.mu, mu, 1e-9) << "r " << r << " eps " << eps;
            EXPECT_NEAR(p.mu_s, mu_s, 1e-9);
            EXPECT_NEAR(p.nu, nu, 1e-12);
            EXPECT_EQ(p.ray_hits_ground, hits);
          }
        }
      }
    }
  }
}

TEST(ScatteringMapping, TexelCentresStayInTheDomain) {
  // Every texel of the default Earth table: r in [Rb, Rt], mu and nu in
  // [-1, 1], mu_s in [mu_s_min, 1], nu geometric, and a ray of length d >= 0
  // that ends where its half says (ground or top). The first and last texel
  // of each axis sit on the ends of its range.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const ScatteringShape shape;
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const ScatteringTexelGrid grid = scattering_texel_grid(atm, shape);
  for (int z = 0; z < shape.r_size; ++z)
    for (int y = 0; y < shape.mu_size; ++y)
      for (int x = 0; x < shape.texture_width(); ++x) {
        const ScatteringParams p = grid.params(x, y, z);
        ASSERT_GE(p.r, rb);
        ASSERT_LE(p.r, rt);
        ASSERT_LE(std::abs(p.mu), 1.0);
        ASSERT_LE(std::abs(p.nu), 1.0);
        ASSERT_GE(p.mu_s, shape.mu_s_min - 1e-15);
        ASSERT_LE(p.mu_s, 1.0);
        const double spread = std::sqrt((1 - p.mu * p.mu) * (1 - p.mu_s * p.mu_s));
        ASSERT_GE(p.nu, p.mu * p.mu_s - spread - 1e-15);
        ASSERT_LE(p.nu, p.mu * p.mu_s + spread + 1e-15);
        const double mu_h = mu_horizon(atm, p.r);
        if (p.ray_hits_ground) {
          ASSERT_LE(p.mu, mu_h + 1e-9);
        } else {
          ASSERT_GE(p.mu, mu_h - 1e-9);
        }
        const double d = distance_to_nearest_boundary(rb, rt, p.r, p.mu, p.ray_hits_ground);
        ASSERT_TRUE(std::isfinite(d));
        ASSERT_GE(d, 0.0);
      }
  EXPECT_EQ(grid.r.front(), rb);
  EXPECT_NEAR(grid.r.back(), rt, 1e-6);
  EXPECT_NEAR(grid.mu_s.front(), shape.mu_s_min, 1e-12);
  EXPECT_EQ(grid.mu_s.back(), 1.0);
  EXPECT_EQ(grid.nu.front(), -1.0);
  EXPECT_EQ(grid.nu.back(), 1.0);
  const int z = 5, half = shape.mu_size / 2;
  EXPECT_NEAR(grid.params(0, half, z).mu, 1.0, 1e-12);                     // zenith
  EXPECT_NEAR(grid.params(0, half - 1, z).mu, -1.0, 1e-12);                // nadir
  EXPECT_NEAR(grid.params(0, 0, z).mu, mu_horizon(atm, grid.r[z]), 1e-9);  // horizon, ground side
  EXPECT_NEAR(grid.params(0, shape.mu_size - 1, z).mu, mu_horizon(atm, grid.r[z]),
              1e-9);  // sky side
}

TEST(ScatteringMapping, TexelGridEqualsTexelParams) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const ScatteringTexelGrid grid = scattering_texel_grid(atm, kSmall);
  for (int z = 0; z < kSmall.r_size; z += 3)
    for (int y = 0; y < kSmall.mu_size; y += 5)
      for (int x = 0; x < kSmall.texture_width(); ++x) {
        const ScatteringParams a = grid.params(x, y, z),
                               b = scattering_texel_params(atm, kSmall, x, y, z);
        ASSERT_EQ(a.r, b.r);
        ASSERT_EQ(a.mu, b.mu);
        ASSERT_EQ(a.mu_s, b.mu_s);
        ASSERT_EQ(a.nu, b.nu);
        ASSERT_EQ(a.ray_hits_ground, b.ray_hits_ground);
      }
}

TEST(ScatteringMapping, MuSMinIsTheFirstTexel) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  for (double degrees : {102.0, 120.0}) {
    ScatteringShape shape = kSmall;
    shape.mu_s_min = std::cos(degrees * kPi / 180.0);
    EXPECT_NEAR(scattering_texel_params(atm, shape, 0, 40, 3).mu_s, shape.mu_s_min, 1e-12);
    // Below mu_s_min the mapping clamps to the first texel centre.
    const glm::dvec4 below =
        scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, atm.bottom_radius_m, 0.5, -0.95, 0.0, false);
    EXPECT_NEAR(below.y, 0.5 / shape.mu_s_size, 1e-12);
  }
}

TEST(ScatteringShapeCheck, RejectsUnusableShapes) {
  ScatteringShape odd = kSmall;
  odd.mu_size = 63;
  EXPECT_THROW(check_scattering_shape(odd), Error);
  ScatteringShape low = kSmall;
  low.mu_s_min = -1.0;
  EXPECT_THROW(check_scattering_shape(low), Error);
  try {
    ScatteringShape one = kSmall;
    one.nu_size = 1;
    check_scattering_shape(one);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "scattering table: expected r >= 2, mu even >= 4, mu_s >= 2, nu >= 2 texels, got "
              "16 x 64 x 16 x 1");
  }
  Metadata meta;
  set_scattering_shape_metadata(meta, kSmall);
  const ScatteringShape back = scattering_shape_from_metadata(meta);
  EXPECT_EQ(back.r_size, kSmall.r_size);
  EXPECT_EQ(back.mu_size, kSmall.mu_size);
  EXPECT_EQ(back.mu_s_size, kSmall.mu_s_size);
  EXPECT_EQ(back.nu_size, kSmall.nu_size);
  EXPECT_EQ(back.mu_s_min, kSmall.mu_s_min);
}

// ---- Media groups -------------------------------------------------------------

TEST(ScatteringPhases, SplitsRayleighAndMie) {
  const ScatteringPhases p = scattering_phases(fixtures::earth_atmosphere());
  EXPECT_TRUE(p.has_rayleigh);
  EXPECT_TRUE(p.has_mie);
  EXPECT_EQ(p.rayleigh_per_m, glm::dvec3(5.802e-6, 13.558e-6, 33.1e-6));
  EXPECT_EQ(p.mie_per_m, glm::dvec3(3.996e-6));
  EXPECT_EQ(p.mie_g, 0.8);
  EXPECT_EQ(p.mie(0.3), cornette_shanks_phase(0.3, 0.8));
  glm::dvec3 rayleigh, mie;
  scattering_by_group(fixtures::earth_atmosphere(), 1.2e3, rayleigh, mie);
  EXPECT_NEAR(mie.r, 3.996e-6 * std::exp(-1.0), 1e-20);
  EXPECT_NEAR(rayleigh.b, 33.1e-6 * std::exp(-0.15), 1e-18);

  Atmosphere two_mie = fixtures::earth_atmosphere();
  two_mie.components.push_back(fixtures::make_component("dust", glm::dvec3(1e-6), glm::dvec3(0.0),
                                                        exponential_profile(3e3),
                                                        PhaseKind::cornette_shanks, 0.5));
  EXPECT_THROW(scattering_phases(two_mie), Error);
}

// ---- Ray quadrature -------------------------------------------------------------

TEST(RayQuadrature, ExactForConstantsAndInsideTheRay) {
  const double rb = 6360e3, rt = 6460e3;
  std::vector<RayNode> nodes;
  for (double r : {rb, rb + 5e3, rt}) {
    for (double mu : {1.0, 0.3, 0.0, -0.05, -0.2, -1.0}) {
      const bool hits = ray_intersects_ground(rb, r, mu);
      const double d = distance_to_nearest_boundary(rb, rt, r, mu, hits);
      ray_quadrature(r, mu, d, 50, nodes);
      if (d == 0.0) {
        EXPECT_TRUE(nodes.empty());
        continue;
      }
      EXPECT_EQ(nodes.size(), 51u);  // 17 segments of 3 nodes
      double sum = 0.0;
      for (const RayNode& n : nodes) {
        ASSERT_GT(n.s, 0.0);
        ASSERT_LT(n.s, d);
        ASSERT_GT(n.weight, 0.0);
        sum += n.weight;
      }
      EXPECT_NEAR(sum, d, 1e-12 * d) << r << " " << mu;
    }
  }
}

TEST(RayQuadrature, ExponentialDensityAlongVerticalAndGrazingRays) {
  // Vertical: int_0^d exp(-(h0 + s)/H) ds = H (exp(-h0/H) - exp(-(h0 + d)/H)).
  // Grazing (mu = 0 at the ground, through no perigee): compared with a
  // midpoint rule of 2e6 steps (error ~ (ds/H)^2/24 ~ 1e-9 for ds = 0.5 m).
  const double rb = 6360e3, rt = 6460e3;
  std::vector<RayNode> nodes;
  for (double H : {1.2e3, 8e3}) {
    ray_quadrature(rb, 1.0, rt - rb, 50, nodes);
    double sum = 0.0;
    for (const RayNode& n : nodes) sum += n.weight * std::exp(-n.s / H);
    const double exact = H * (1.0 - std::exp(-(rt - rb) / H));
    EXPECT_NEAR(sum, exact, 1e-5 * exact) << "H " << H;

    const double d = distance_to_top_boundary(rt, rb + 2e3, -0.01);
    ray_quadrature(rb + 2e3, -0.01, d, 50, nodes);
    auto density = [&](double s) { return std::exp(-(radius_after(rb + 2e3, -0.01, s) - rb) / H); };
    sum = 0.0;
    for (const RayNode& n : nodes) sum += n.weight * density(n.s);
    double reference = 0.0;
    const int steps = 2000000;
    for (int i = 0; i < steps; ++i) reference += density((i + 0.5) * d / steps) * d / steps;
    EXPECT_NEAR(sum, reference, 1e-5 * reference) << "H " << H;
  }
}

// ---- Transmittance reader ---------------------------------------------------------

TEST(TransmittanceReader, MatchesTheLutLookups) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const TransmittanceReader reader(lut, atm);
  const double rb = atm.bottom_radius_m;
  for (double h : {0.0, 300.0, 7e3, 45e3, 100e3}) {
    for (double mu : {1.0, 0.7, 0.1, 0.0, -0.02, -0.1, -0.6, -1.0}) {
      const double r = rb + h;
      const glm::dvec3 a = reader.to_top(r, mu), b = lookup_transmittance_to_top(lut, atm, r, mu);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-13) << h << " " << mu;
      const bool hits = ray_intersects_ground(rb, r, mu);
      const double d = distance_to_nearest_boundary(rb, atm.top_radius_m, r, mu, hits);
      for (double f : {0.1, 0.5, 1.0}) {
        const glm::dvec3 t1 = reader.between(r, mu, f * d, hits);
        const glm::dvec3 t2 = lookup_transmittance(lut, atm, r, mu, f * d, hits);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(t1[c], t2[c], 1e-12) << h << " " << mu;
      }
    }
  }
  // Sun visibility: the full disk above the horizon, none below it.
  const TransmittanceReader::Row row = reader.row(rb + 10e3);
  const double mu_h = mu_horizon(atm, rb + 10e3), alpha = atm.sun_angular_radius_rad;
  EXPECT_EQ(reader.to_sun(row, mu_h - 2 * alpha), glm::dvec3(0.0));
  EXPECT_EQ(reader.to_sun(row, mu_h + 2 * alpha), reader.to_top(row, mu_h + 2 * alpha));
  const glm::dvec3 half = reader.to_sun(row, mu_h);
  EXPECT_NEAR(half.r, 0.5 * reader.to_top(row, mu_h).r, 1e-12);
}


// ---- Single scattering: closed forms ------------------------------------------------

TEST(ComputeSingleScattering, EmptyAtmosphereScattersNothing) {
  const Atmosphere atm = fixtures::empty_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {32, 8, 10}, BakeContext{});
  const SingleScattering s =
      compute_single_scattering(atm, lut, atm.bottom_radius_m, 0.5, 0.5, 0.25, false, 50);
  EXPECT_EQ(s.rayleigh, glm::dvec3(0.0));
  EXPECT_EQ(s.mie, glm::dvec3(0.0));
}

TEST(ComputeSingleScattering, UniformSlabLookingAtTheSun) {
  // A slab of constant sigma_s, sigma_t filling the shell; the sun straight
  // along the view ray (mu_s = mu, nu = 1). Light scattered at distance s
  // entered the atmosphere where the view ray leaves it: it travelled d - s
  // to reach y and s to reach x, so T(x, y) T_sun(y) = exp(-sigma_t d) for
  // every s and
  //   S = E sigma_s int_0^d exp(-sigma_t d) ds = E sigma_s d exp(-sigma_t d).
  // T(x, y) is integrated along the ray (exact for a constant medium), so
  // what remains is the LUT's error toward the sun, measured along the ray.
  const glm::dvec3 sigma_s(2e-6, 5e-6, 1.2e-5), sigma_a(1e-6, 0.0, 3e-6);
  Atmosphere atm = fixtures::uniform_slab_atmosphere(sigma_s, sigma_a);
  atm.sun_illuminance = glm::dvec3(1.0, 2.0, 3.0);
  const Texture lut = bake_transmittance_lut(atm, {512, 128, 40}, BakeContext{});
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  for (double h : {0.0, 2e3, 40e3}) {
    for (double mu : {1.0, 0.6, 0.2, 0.05}) {
      const double r = rb + h, d = distance_to_top_boundary(rt, r, mu);
      const SingleScattering s = compute_single_scattering(atm, lut, r, mu, mu, 1.0, false, 50);
      const double lut_error = fixtures::sun_lut_error_along_ray(
          lut, atm, r, mu, d, [&](double s) { return (sigma_s + sigma_a) * (d - s); });
      EXPECT_LT(lut_error, 2e-3);  // a 512 x 128 LUT, worst at grazing mu
      for (int c = 0; c < 3; ++c) {
        const double exact =
            atm.sun_illuminance[c] * sigma_s[c] * d * std::exp(-(sigma_s[c] + sigma_a[c]) * d);
        EXPECT_NEAR(s.rayleigh[c], exact, (lut_error + 1e-9) * exact) << h << " " << mu;
      }
      EXPECT_EQ(s.mie, glm::dvec3(0.0));  // the slab has the Rayleigh phase
    }
  }
}

TEST(ComputeSingleScattering, ExponentialLayersVerticalRayZenithSun) {
  // Vertical ray from the ground, sun at the zenith (mu = mu_s = nu = 1):
  // as above T(x, y) T_sun(y) = T(ground -> top) = exp(-tau) for every y, with
  // tau = sum_c sigma_t,c H_c (1 - exp(-Ht/H_c)), and
  //   S_c = E sigma_s,c exp(-tau) int_0^Ht exp(-h/H_c) dh
  //       = E sigma_s,c exp(-tau) H_c (1 - exp(-Ht/H_c)).
  // Allowed: the LUT's error toward the sun (its rows interpolate in r),
  // measured along the ray, and 1e-5 for the ray quadrature on a 1.2 km and
  // an 8 km scale height over 100 km.
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.components.pop_back();  // no ozone: tau in closed form
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const double top_h = atm.top_radius_m - atm.bottom_radius_m;
  const MediumComponent& ray = atm.components[0];
  const MediumComponent& mie = atm.components[1];
  // sum_c sigma_t,c int_h^Ht exp(-h'/H_c) dh'
  auto depth_above = [&](double h) {
    auto column = [&](double H) { return H * (std::exp(-h / H) - std::exp(-top_h / H)); };
    return ray.scattering_per_m * column(8e3) +
           (mie.scattering_per_m + mie.absorption_per_m) * column(1.2e3);
  };
  const glm::dvec3 tau = depth_above(0.0);
  auto column = [&](double H) { return H * (1.0 - std::exp(-top_h / H)); };
  const SingleScattering s =
      compute_single_scattering(atm, lut, atm.bottom_radius_m, 1.0, 1.0, 1.0, false, 50);
  const double lut_error =
      fixtures::sun_lut_error_along_ray(lut, atm, atm.bottom_radius_m, 1.0, top_h, depth_above);
  EXPECT_LT(lut_error, 1e-3);
  for (int c = 0; c < 3; ++c) {
    const double rayleigh = ray.scattering_per_m[c] * std::exp(-tau[c]) * column(8e3);
    const double mie_exact = mie.scattering_per_m[c] * std::exp(-tau[c]) * column(1.2e3);
    EXPECT_NEAR(s.rayleigh[c], rayleigh, (lut_error + 1e-5) * rayleigh) << c;
    EXPECT_NEAR(s.mie[c], mie_exact, (lut_error + 1e-5) * mie_exact) << c;
  }
}

TEST(ComputeSingleScattering, SunBelowTheHorizonOfTheWholeRay) {
  // Looking down from 1 km toward the ground, the sun 30 degrees below the
  // horizon at the opposite azimuth: at a point s along the ray the sun's
  // cosine is (r mu_s + s nu) / r_s < -0.49 with nu = -0.5, far below the
  // horizon (-0.018 at 1 km): every point is in the planet's shadow.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const double mu = -0.5, mu_s = -0.5, sin_v = std::sqrt(0.75);
  const double nu = mu * mu_s - sin_v * sin_v;  // opposite azimuths
  const SingleScattering s =
      compute_single_scattering(atm, lut, atm.bottom_radius_m + 1e3, mu, mu_s, nu, true, 50);
  EXPECT_EQ(s.rayleigh, glm::dvec3(0.0));
  EXPECT_EQ(s.mie, glm::dvec3(0.0));
}

// ---- Bake and lookups -------------------------------------------------------------

TEST(BakeSingleScattering, TexelsEqualTheRayIntegralAtTheirCentre) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const SingleScatteringTables t = bake_single_scattering(atm, lut, kSmall, 30, BakeContext{});
  EXPECT_EQ(t.rayleigh.width, kSmall.nu_size * kSmall.mu_s_size);
  EXPECT_EQ(t.rayleigh.height, kSmall.mu_size);
  EXPECT_EQ(t.rayleigh.depth, kSmall.r_size);
  for (int z = 0; z < kSmall.r_size; z += 5)
    for (int y = 0; y < kSmall.mu_size; y += 7)
      for (int x = 0; x < kSmall.texture_width(); x += 3) {
        const ScatteringParams p = scattering_texel_params(atm, kSmall, x, y, z);
        const SingleScattering s =
            compute_single_scattering(atm, lut, p.r, p.mu, p.mu_s, p.nu, p.ray_hits_ground, 30);
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(t.rayleigh.at(x, y, z, 0, c), float(s.rayleigh[c]))
              << x << " " << y << " " << z;
          ASSERT_EQ(t.mie.at(x, y, z, 0, c), float(s.mie[c]));
        }
      }
  for (float v : t.rayleigh.data) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
}

TEST(BakeSingleScattering, SameDataForOneAndTwoThreads) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  TexelVector one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_single_scattering(atm, lut, kSmall, 30, BakeContext{}).mie.data;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_single_scattering(atm, lut, kSmall, 30, BakeContext{}).mie.data;
  }
  EXPECT_TRUE(one == two);
}

TEST(LookupScattering, ReadsTexelsAndAppliesThePhases) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const SingleScatteringTables t = bake_single_scattering(atm, lut, kSmall, 20, BakeContext{});
  const ScatteringPhases phases = scattering_phases(atm);
  // At a texel whose nu is its slice's (not clamped), the read is the texel.
  int checked = 0;
  for (int z : {0, 7}) {
    for (int y : {3, 20, 40, 60}) {
      const int x = 2 * kSmall.mu_s_size + 11;  // nu slice 2: nu = 1/3
      const ScatteringParams p = scattering_texel_params(atm, kSmall, x, y, z);
      if (std::abs(p.nu - 1.0 / 3.0) > 1e-12) continue;
      ++checked;
      const glm::dvec3 rgb = lookup_scattering_rgb(t.rayleigh, kSmall, atm, p.r, p.mu, p.mu_s, p.nu,
                                                   p.ray_hits_ground);
      const glm::dvec3 L = lookup_scattering(t.rayleigh, t.mie, kSmall, atm, p.r, p.mu, p.mu_s,
                                             p.nu, p.ray_hits_ground);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(rgb[c], t.rayleigh.at(x, y, z, 0, c), 1e-6 * rgb[c]);
        const double expected = phases.rayleigh(p.nu) * t.rayleigh.at(x, y, z, 0, c) +
                                phases.mie(p.nu) * t.mie.at(x, y, z, 0, c);
        EXPECT_NEAR(L[c], expected, 1e-6 * expected);
      }
    }
  }
  EXPECT_GE(checked, 4);
}

TEST(LookupScattering, MieFromAlphaIsExactWhenMieFollowsRayleigh) {
  // Bodare & Sandberg eq. 19 recovers Mie RGB from Rayleigh RGB and Mie red:
  // mie = rgb (A / R) (beta_R.r / beta_M.r) (beta_M / beta_R). It is exact
  // when S_M / S_R = beta_M / beta_R per channel, i.e. when both groups have
  // the same density profile: then S_c = beta_c int rho T T_sun ds for the
  // same integral. Two uniform slabs over the same shell.
  Atmosphere atm =
      fixtures::uniform_slab_atmosphere(glm::dvec3(5.8e-6, 13.5e-6, 33.1e-6), glm::dvec3(0.0));
  atm.components.push_back(fixtures::make_component("mie", glm::dvec3(4e-6, 3e-6, 2e-6),
                                                    glm::dvec3(4e-7), atm.components[0].density,
                                                    PhaseKind::cornette_shanks, 0.76));
  const Texture lut = bake_transmittance_lut(atm, {128, 32, 20}, BakeContext{});
  const SingleScatteringTables t = bake_single_scattering(atm, lut, kSmall, 20, BakeContext{});
  Texture combined(t.rayleigh.width, t.rayleigh.height, t.rayleigh.depth, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < t.rayleigh.texel_count(); ++i) {
    for (int c = 0; c < 3; ++c) combined.data[4 * i + c] = t.rayleigh.data[3 * i + c];
    combined.data[4 * i + 3] = t.mie.data[3 * i];
  }
  const double rb = atm.bottom_radius_m;
  for (double h : {10.0, 3e3, 30e3})
    for (double mu : {0.9, 0.2, -0.3})
      for (double nu : {0.95, 0.0}) {
        const double r = rb + h, mu_s = 0.4;
        const double spread = std::sqrt((1 - mu * mu) * (1 - mu_s * mu_s));
        const double n = std::clamp(nu, mu * mu_s - spread, mu * mu_s + spread);
        const bool hits = ray_intersects_ground(rb, r, mu);
        const glm::dvec3 separate =
            lookup_scattering(t.rayleigh, t.mie, kSmall, atm, r, mu, mu_s, n, hits);
        const glm::dvec3 from_alpha =
            lookup_scattering(combined, Texture{}, kSmall, atm, r, mu, mu_s, n, hits);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(from_alpha[c], separate[c], 1e-5 * separate[c]);
      }
}

}  // namespace
}  // namespace skybake

// Tests of bake_bruneton (atmosphere/scattering_orders.hpp), the whole 4D
// bake: its outputs' shapes, channels and metadata, physical skies and the
// orders' own tables, determinism across thread counts, progress, refused
// specs, and where half floats lose against float32.
#include "atmosphere/scattering_orders.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <mutex>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error.hpp"
#include "core/half.hpp"
#include "core/math.hpp"
#include "support/order_progress_checks.hpp"
#include "support/test_atmospheres.hpp"
#include "support/test_scattering_specs.hpp"

namespace skybake {
namespace {

// ---- The bake ---------------------------------------------------------------------

TEST(BakeBruneton, ShapesChannelsAndMetadata) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  BrunetonSpec spec = fixtures::orders_test_spec(3);
  std::mutex mutex;
  double last_progress = -1.0;
  bool monotone = true;
  BakeContext ctx;
  ctx.on_progress = [&](double f) {
    std::lock_guard<std::mutex> lock(mutex);
    monotone = monotone && f >= 0.0 && f <= 1.0;
    last_progress = std::max(last_progress, f);
  };
  const BrunetonTextures t = bake_bruneton(atm, lut, spec, ctx);
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last_progress, 1.0);
  EXPECT_EQ(t.scattering.width, spec.nu_size * spec.mu_s_size);
  EXPECT_EQ(t.scattering.height, spec.mu_size);
  EXPECT_EQ(t.scattering.depth, spec.r_size);
  EXPECT_EQ(t.scattering.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(t.single_mie.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(t.irradiance.width, 32);
  EXPECT_EQ(t.irradiance.height, 8);
  EXPECT_EQ(t.orders_used, 3);
  EXPECT_EQ(t.residuals.size(), 2u);
  EXPECT_EQ(t.last_residual, t.residuals.back());
  for (size_t i = 0; i < t.single_mie.texel_count(); ++i)
    ASSERT_EQ(t.scattering.data[4 * i + 3], t.single_mie.data[3 * i]);
  const Metadata& m = t.scattering.metadata;
  EXPECT_EQ(meta_string(m, "parameterization"), "bruneton_4d_scattering");
  EXPECT_EQ(meta_int(m, "orders"), 3);
  EXPECT_EQ(meta_double(m, "last_residual"), t.last_residual);
  EXPECT_EQ(meta_double(m, "mu_s_min"), kBrunetonMuSMin);
  EXPECT_EQ(meta_int(m, "mie_in_alpha"), 1);
  EXPECT_EQ(scattering_shape_from_metadata(m).mu_s_size, spec.mu_s_size);
  for (const char* key : {"quantity", "channel_layout", "mapping", "units"})
    EXPECT_FALSE(meta_string(m, key).empty()) << key;
  EXPECT_GT(meta_double3(m, "rayleigh_scattering_per_m").x, 0.0);
  EXPECT_GT(meta_double3(m, "mie_scattering_per_m").x, 0.0);
  EXPECT_GT(meta_double(m, "mie_g"), 0.5) << "Earth's aerosols scatter forward";
  EXPECT_EQ(meta_int(t.irradiance.metadata, "includes_direct"), 0);
  EXPECT_EQ(meta_int(t.irradiance.metadata, "orders"), 3);

  // Separate Mie, irradiance with the direct part summed in.
  spec.combined_mie_alpha = false;
  spec.irradiance_includes_direct = true;
  const BrunetonTextures u = bake_bruneton(atm, lut, spec, BakeContext{});
  EXPECT_EQ(u.scattering.channels, (std::vector<std::string>{"R", "G", "B"}));
  for (size_t i = 0; i < u.single_mie.texel_count(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(u.scattering.data[3 * i + c], t.scattering.data[4 * i + c]);
  for (size_t i = 0; i < u.irradiance.data.size(); ++i)
    ASSERT_NEAR(u.irradiance.data[i], t.irradiance.data[i] + t.direct_irradiance.data[i],
                1e-6f * u.irradiance.data[i]);
}

TEST(BakeBruneton, OrdersAddLightAndTheSkyIsPhysical) {
  // More orders only add light; Earth's sky is brighter toward the horizon
  // than at the zenith for a high sun, and blue dominates the zenith.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const BrunetonTextures one = bake_bruneton(atm, lut, fixtures::orders_test_spec(1), BakeContext{});
  const BrunetonTextures three = bake_bruneton(atm, lut, fixtures::orders_test_spec(3), BakeContext{});
  EXPECT_EQ(one.orders_used, 1);
  EXPECT_EQ(one.last_residual, 1.0);
  for (size_t i = 0; i < one.scattering.data.size(); ++i)
    ASSERT_GE(three.scattering.data[i], one.scattering.data[i]);
  for (size_t i = 0; i < one.irradiance.data.size(); ++i)
    ASSERT_GE(three.irradiance.data[i], one.irradiance.data[i]);
  const double rb = atm.bottom_radius_m;
  const glm::dvec3 zenith =
      lookup_scattering(three.scattering, Texture{}, three.shape, atm, rb, 1.0, 0.8, 0.8, false);
  const glm::dvec3 horizon =
      lookup_scattering(three.scattering, Texture{}, three.shape, atm, rb, 0.05, 0.8, 0.05, false);
  EXPECT_GT(zenith.b, zenith.g);
  EXPECT_GT(zenith.g, zenith.r);
  EXPECT_GT(horizon.g, zenith.g);
}

TEST(BakeBruneton, OrdersAboveOneReadBackAsTheOrdersOwnTable) {
  // The table stores orders >= 2 as DeltaS / p_R in its Rayleigh channels
  // and an engine multiplies the read by p_R(nu) (header). A view in the
  // sun's vertical plane has the largest or smallest nu its mu and mu_s
  // allow, so its taps at the neighbouring mu, mu_s texels hold slices whose
  // nu those texels had to clamp. Divided by p_R at the clamped nu, the
  // read would give orders >= 2 up to 18% too bright toward the sun's
  // azimuth (Rayleigh only, sun 30 degrees from the zenith; the path tracer
  // has them flat across azimuths within 3%). Here order 2 read through the table
  // (table minus the single-scattering tables, same taps) must match the
  // order's own DeltaS table read directly, within 2.5%, in and out of the
  // sun's plane. Default shape: the one engines ship.
  Atmosphere atm = fixtures::earth_atmosphere();
  atm.ground_albedo = glm::dvec3(0.0);
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  BrunetonSpec spec;
  spec.orders = 2;
  spec.combined_mie_alpha = false;
  const BrunetonTextures table = bake_bruneton(atm, lut, spec, BakeContext{});
  const ScatteringShape shape = spec.shape();
  const ScatteringPhases phases = scattering_phases(atm);
  const SingleScatteringTables single =
      bake_single_scattering(atm, lut, shape, spec.ray_nodes, BakeContext{});
  const ScatteringOrder order1{&single.rayleigh, &single.mie, nullptr, &phases};
  // Order 2 as the bake makes it (scattering_orders.hpp, J_k in the sun's frame).
  SunFrameDensity density;
  bake_sun_frame_density(atm, lut, shape, order1, GroundIrradiance{}, spec.density_directions,
                         sun_frame_azimuths(shape), BakeContext{}, density);
  divide_by_scattering(atm, density);
  Texture delta;
  MultipleScatteringWork work;
  bake_multiple_scattering(atm, density, spec.ray_nodes, BakeContext{}, delta, work);
  const double r = atm.bottom_radius_m + 200.0, deg = kPi / 180.0;
  for (double sun_elevation : {60.0, 20.0})
    for (double elevation : {60.0, 20.0, 5.0})
      for (double azimuth : {0.0, 90.0, 180.0}) {
        const double e = elevation * deg, a = azimuth * deg, s = sun_elevation * deg;
        const double mu = std::sin(e), mu_s = std::sin(s);
        const double nu = std::cos(e) * std::cos(a) * std::cos(s) + mu * mu_s;
        const glm::dvec3 read =
            lookup_scattering(table.scattering, table.single_mie, shape, atm, r, mu, mu_s, nu,
                              false) -
            lookup_scattering(single.rayleigh, single.mie, shape, atm, r, mu, mu_s, nu, false);
        const glm::dvec3 own = lookup_scattering_rgb(delta, shape, atm, r, mu, mu_s, nu, false);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(read[c] / own[c], 1.0, 0.025)
              << "sun " << sun_elevation << " view " << elevation << " azimuth " << azimuth
              << " channel " << c;
      }
}

TEST(BakeBruneton, SameDataForOneAndTwoThreads) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  BrunetonTextures one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_bruneton(atm, lut, fixtures::orders_test_spec(3), BakeContext{});
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = bake_bruneton(atm, lut, fixtures::orders_test_spec(3), BakeContext{});
  }
  EXPECT_TRUE(one.scattering.data == two.scattering.data);
  EXPECT_TRUE(one.irradiance.data == two.irradiance.data);
  EXPECT_EQ(one.last_residual, two.last_residual);
}

TEST(BakeBruneton, ProgressFollowsTheOrdersAToleranceTakes) {
  // 50x Earth to a tolerance: many orders, far fewer than the cap. The
  // fraction never decreases, reaches 1 only at the end, and is past half
  // when the last order starts (with each order weighted 1 / (max_orders +
  // 1), it would start near 28% and the bake jump to 1 from there). One
  // thread: the reports arrive in order.
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const Atmosphere atm = fixtures::scaled_atmosphere(fixtures::earth_atmosphere(), 50.0);
  const Texture lut = bake_transmittance_lut(atm, {128, 32, 40}, BakeContext{});
  BrunetonSpec spec = fixtures::dense_medium_spec();
  spec.tolerance = 5e-3;
  spec.max_orders = 400;
  std::vector<double> seen;
  BakeContext ctx;
  ctx.on_progress = [&](double f) { seen.push_back(f); };
  const BrunetonTextures t = bake_bruneton(atm, lut, spec, ctx);
  ASSERT_GT(t.orders_used, 10);
  ASSERT_LT(t.orders_used, spec.max_orders);
  // Each order k >= 2 reports once per (r, mu_s) pair of its density and
  // once per (r, mu) row of its DeltaS; the bake then reports 1.
  const size_t per_order = size_t(spec.r_size) * (spec.mu_s_size + spec.mu_size);
  fixtures::expect_progress_follows_the_orders(seen, per_order, t.orders_used);
}

TEST(BakeBruneton, RejectsBadSpecs) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, {16, 4, 5}, BakeContext{});
  auto message = [&](BrunetonSpec spec) {
    try {
      bake_bruneton(atm, lut, spec, BakeContext{});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BrunetonSpec spec = fixtures::orders_test_spec(0);
  EXPECT_EQ(message(spec), "scattering: expected orders in [1, 1000], got 0");
  spec = fixtures::orders_test_spec(4);
  spec.tolerance = -1;
  EXPECT_EQ(message(spec), "scattering: expected tolerance >= 0, got -1");
  spec = fixtures::orders_test_spec(4);
  spec.tolerance = 1e-3;
  spec.max_orders = 1;
  EXPECT_EQ(message(spec), "scattering: expected max_orders in [2, 1000], got 1");
  spec = fixtures::orders_test_spec(4);
  spec.mu_size = 31;
  EXPECT_NE(message(spec).find("mu even >= 4"), std::string::npos);
  spec = fixtures::orders_test_spec(4);
  spec.mu_s_min = 0.5;
  EXPECT_EQ(message(spec), "scattering table: expected mu_s_min in (-1, 0], got 0.5");
}

// ---- Half vs float ------------------------------------------------------------------

float round_to_half(float v) {
  return float_from_half(half_from_float(v));
}

// The largest relative error of rounding each positive texel to half, in
// half's normal range and below it (2^-14 = 6.1e-5), and the share of
// texels below it.
struct HalfStorageError {
  double normal = 0.0, subnormal = 0.0, subnormal_share = 0.0;
};
HalfStorageError half_storage_error(const TexelVector& values) {
  HalfStorageError e;
  size_t count = 0, small = 0;
  for (float v : values) {
    if (!(v > 0.0f)) continue;
    ++count;
    const double rel = std::abs(double(round_to_half(v)) - v) / v;
    if (v < 6.103515625e-5f) {
      ++small;
      e.subnormal = std::max(e.subnormal, rel);
    } else {
      e.normal = std::max(e.normal, rel);
    }
  }
  e.subnormal_share = count ? double(small) / count : 0.0;
  return e;
}

// The aerial perspective S(x) - T(x, y) S(y) over each length, in float
// arithmetic from the float texels and from half-rounded texels, against
// double arithmetic on the float texels: the largest relative error of each.
struct ApErrors {
  std::vector<double> float_error, half_error;
};
ApErrors aerial_perspective_errors(const Atmosphere& atm, const Texture& lut,
                                   const BrunetonTextures& t, const std::vector<double>& lengths) {
  Texture half_scattering = t.scattering, half_mie = t.single_mie;
  for (float& v : half_scattering.data) v = round_to_half(v);
  for (float& v : half_mie.data) v = round_to_half(v);
  const double rb = atm.bottom_radius_m;
  ApErrors e{std::vector<double>(lengths.size(), 0.0), std::vector<double>(lengths.size(), 0.0)};
  for (size_t li = 0; li < lengths.size(); ++li)
    for (double h : {2.0, 500.0, 3e3})
      for (double mu : {0.3, 0.05, 0.0, -0.02})
        for (double mu_s : {0.9, 0.3, 0.05}) {
          const double nu = mu * mu_s, r = rb + h, l = lengths[li];
          const bool hits = ray_intersects_ground(rb, r, mu);
          if (hits && l >= distance_to_bottom_boundary(rb, r, mu)) continue;
          const double r_y = radius_after(r, mu, l), mu_y = mu_after(r, mu, l, r_y);
          const double mu_s_y = (r * mu_s + l * nu) / r_y;
          const glm::dvec3 T = lookup_transmittance(lut, atm, r, mu, l, hits);
          auto read = [&](const Texture& s, const Texture& m, double rr, double mm, double ss) {
            return lookup_scattering(s, m, t.shape, atm, rr, mm, ss, nu, hits);
          };
          const glm::dvec3 Sx = read(t.scattering, t.single_mie, r, mu, mu_s);
          const glm::dvec3 Sy = read(t.scattering, t.single_mie, r_y, mu_y, mu_s_y);
          const glm::dvec3 Hx = read(half_scattering, half_mie, r, mu, mu_s);
          const glm::dvec3 Hy = read(half_scattering, half_mie, r_y, mu_y, mu_s_y);
          for (int c = 0; c < 3; ++c) {
            const double exact = Sx[c] - T[c] * Sy[c];
            if (!(exact > 0.0)) continue;
            const float f = float(Sx[c]) - float(T[c]) * float(Sy[c]);
            const float hf = float(Hx[c]) - float(T[c]) * float(Hy[c]);
            e.float_error[li] = std::max(e.float_error[li], std::abs(f - exact) / exact);
            e.half_error[li] = std::max(e.half_error[li], std::abs(hf - exact) / exact);
          }
        }
  return e;
}

TEST(ScatteringPrecision, WhereHalfFloatsLose) {
  // Earth, 4 orders. Three measurements, reported as test properties and on
  // stdout:
  //  1. storage: relative error of rounding each texel to half (2^-11 in the
  //     normal range, worse in the subnormal range below 2^-14 = 6.1e-5,
  //     where the 4th order and night-side texels live);
  //  2. the 4th order alone (engines that keep high orders apart);
  //  3. aerial perspective: the light scattered between a viewer x and a
  //     point y at distance l is S(x) - T(x, y) S(y) (Bruneton 2017
  //     GetSkyRadianceToPoint); for short l the two terms nearly cancel and
  //     the storage error is amplified by S / (S - T S). Computed in float
  //     arithmetic from float texels and from half-rounded texels, against
  //     double arithmetic on the float texels.
  // Float32 must keep the aerial-perspective error below 1e-3 from l = 100 m
  // (at 10 m the float rounding of the two reads themselves dominates, ~2e-3);
  // half must be several times worse at every length (why float32 is the
  // default; at 10 m by less). Half's error grows less than 1/l as l shrinks because both
  // reads then share texels and so share their rounding.
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  BrunetonSpec spec = fixtures::orders_test_spec(4);
  spec.nu_size = 8;
  spec.combined_mie_alpha = false;
  const BrunetonTextures t = bake_bruneton(atm, lut, spec, BakeContext{});
  const BrunetonTextures three = bake_bruneton(
      atm, lut,
      [&] {
        BrunetonSpec s = spec;
        s.orders = 3;
        return s;
      }(),
      BakeContext{});

  const HalfStorageError all = half_storage_error(t.scattering.data);
  TexelVector fourth(t.scattering.data.size());
  for (size_t i = 0; i < fourth.size(); ++i)
    fourth[i] = std::max(0.0f, t.scattering.data[i] - three.scattering.data[i]);
  const HalfStorageError order4 = half_storage_error(fourth);
  EXPECT_LE(all.normal, std::ldexp(1.0, -11) * 1.0001);  // half's unit roundoff

  const std::vector<double> lengths = {10.0, 100.0, 1e3, 10e3};
  const ApErrors ap = aerial_perspective_errors(atm, lut, t, lengths);
  const std::vector<double>& float_error = ap.float_error;
  const std::vector<double>& half_error = ap.half_error;
  std::string report = fmt::format(
      "half storage: max rel error {:.2g} (normal range), {:.2g} on the {:.1f} % of texels below "
      "6.1e-5; 4th order alone: {:.2g} normal, {:.2g} on its {:.1f} % subnormal texels.\n",
      all.normal, all.subnormal, 100 * all.subnormal_share, order4.normal, order4.subnormal,
      100 * order4.subnormal_share);
  for (size_t li = 0; li < lengths.size(); ++li) {
    report += fmt::format("aerial perspective over {:g} m: float32 {:.2g}, half {:.2g}\n",
                          lengths[li], float_error[li], half_error[li]);
    RecordProperty(fmt::format("ap_{}m_float", int(lengths[li])),
                   fmt::format("{:.3g}", float_error[li]));
    RecordProperty(fmt::format("ap_{}m_half", int(lengths[li])),
                   fmt::format("{:.3g}", half_error[li]));
    EXPECT_LT(float_error[li], lengths[li] < 100.0 ? 5e-3 : 1e-3) << lengths[li];
    // At 10 m float32's own error is the rounding of the two reads (above),
    // which moves with the last bits of the texels: half need only be twice
    // as bad there, five times from 100 m.
    EXPECT_GT(half_error[li], (lengths[li] < 100.0 ? 2.0 : 5.0) * float_error[li]) << lengths[li];
  }
  RecordProperty("half_storage_normal", fmt::format("{:.3g}", all.normal));
  RecordProperty("half_storage_subnormal", fmt::format("{:.3g}", all.subnormal));
  RecordProperty("half_4th_order_subnormal", fmt::format("{:.3g}", order4.subnormal));
  std::cout << report;
}

}  // namespace
}  // namespace skybake

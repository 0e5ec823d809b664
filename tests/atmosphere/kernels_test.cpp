// Every kernel of the bakers on every SIMD target this CPU runs against the
// one-value functions it stands for, bit for bit (docs/architecture.md
// "Kernels"): the mu_s taps against MuSAxis::tap, single scattering's many
// suns against one sun at a time, the density's Mie sums against one pair
// at a time, the orders' node reads and row blends against one texel at a
// time, the sky-view rows against
// skyview_texel_luminance, the
// multiple-scattering table against compute_multiscattering at its texels,
// the sky references' reads against lookup_sun_transmittance and
// lookup_multiscattering, the transmittance quadrature's node altitudes
// against node_altitude_from_perigee.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/kernels/mie_batch.hpp"
#include "atmosphere/kernels/node_altitudes.hpp"
#include "atmosphere/kernels/node_slice_reads.hpp"
#include "atmosphere/kernels/row_blend.hpp"
#include "atmosphere/kernels/skyview_row_luminance.hpp"
#include "atmosphere/kernels/sun_frame_reads.hpp"
#include "atmosphere/kernels/sun_and_psi_ms_reads.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "support/simd_targets.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

bool same_bits(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

// Earth, the tiny planet and Earth under 1000x Rayleigh (the stiff extreme
// case, whose tables underflow near the ground).
std::vector<Atmosphere> atmospheres() {
  Atmosphere dense = fixtures::earth_atmosphere();
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  return {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense};
}

TEST_P(KernelsOnEachTarget, SkyviewRowsAreOneTexelAtATime) {
  for (const Atmosphere& atm : atmospheres()) {
    const fixtures::SkyLutInputs l = fixtures::bake_sky_lut_inputs(atm);
    const MultiscatteringMapping mapping = multiscattering_mapping_of(l.multiscattering);
    ASSERT_EQ(mapping.sun, SunMapping::linear);  // the kernel's mapping
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    // Ground, mid-air and space viewers, rays to the ground and to space,
    // suns on both sides of the horizon; 11 texels: every group size.
    for (double r : {rb + 1.0, rb + 0.4 * (rt - rb), rt + 20e3})
      for (double mu : {-0.7, -0.05, 0.1, 0.9})
        for (double sun_zenith : {0.3, 1.5, 1.75}) {
          const SkyviewRowMarch row = march_skyview_row(atm, l.transmittance, l.multiscattering,
                                                        mapping, r, mu, 12,
                                                        StepDistribution::quadratic);
          const int n = 11;
          std::vector<double> cos_phi(n), nu(n);
          for (int x = 0; x < n; ++x) {
            cos_phi[x] = std::cos(kPi * x / (n - 1));
            nu[x] = clamp_cosine(std::cos(sun_zenith) * mu +
                                 std::sin(sun_zenith) * safe_sqrt(1.0 - mu * mu) * cos_phi[x]);
          }
          const double cos_s = std::cos(sun_zenith), sin_s = std::sin(sun_zenith);
          std::vector<glm::dvec3> lanes(n), one(n), scratch;
          skyview_row_luminance(row, atm, l.transmittance, l.multiscattering, cos_phi.data(),
                                nu.data(), n, cos_s, sin_s, lanes.data());
          for (int x = 0; x < n; ++x)
            one[x] = skyview_texel_luminance(row, atm, l.transmittance, l.multiscattering,
                                             cos_phi[x], cos_s, sin_s, nu[x], scratch);
          EXPECT_TRUE(same_bits(lanes, one)) << r << " " << mu << " " << sun_zenith;
        }
  }
}

TEST_P(KernelsOnEachTarget, MultiscatteringTexelsAreComputeMultiscattering) {
  // Both direction rules (unweighted and weighted), both sun mappings, a
  // planet whose rays mostly end on its ground; rows of 11 suns.
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()}) {
    const Texture lut = bake_transmittance_lut(atm, {64, 16, 40}, BakeContext{});
    for (DirectionQuadrature q : {DirectionQuadrature::fibonacci, DirectionQuadrature::symmetric_gauss})
      for (SunMapping sun : {SunMapping::linear, SunMapping::terminator}) {
        MultiscatteringLutSpec spec{11, 6, 24, 8};
        spec.quadrature = q;
        spec.sun_mapping = sun;
        const Texture table = bake_multiscattering_lut(atm, lut, spec, {});
        const MultiscatteringMapping mapping = multiscattering_mapping_of(table);
        for (int y = 0; y < spec.height; ++y) {
          const double v = texel_center(y, spec.height);
          const double r =
              r_mu_s_from_multiscattering_uv(atm, {0.5, v}, spec.width, spec.height, mapping).r;
          const SphereRule rule = multiscattering_rule(q, spec.directions, atm, r);
          for (int x = 0; x < spec.width; ++x) {
            const double mu_s = clamp_cosine(
                r_mu_s_from_multiscattering_uv(atm, {texel_center(x, spec.width), v}, spec.width,
                                               spec.height, mapping)
                    .mu_s);
            const glm::dvec3 psi =
                compute_multiscattering(atm, lut, r, mu_s, rule, spec.steps).psi_ms;
            for (int c = 0; c < 3; ++c)
              ASSERT_EQ(table.at(x, y, 0, 0, c), float(psi[c]))
                  << int(q) << " " << int(sun) << " " << x << " " << y;
          }
        }
      }
  }
}

TEST_P(KernelsOnEachTarget, SunAndPsiMsReadsAreTheOneValueLookups) {
  for (const Atmosphere& atm : atmospheres()) {
    const Texture t = bake_transmittance_lut(atm, {64, 32, 16}, {});
    MultiscatteringLutSpec terminator{12, 10, 16, 12};
    terminator.sun_mapping = SunMapping::terminator;
    terminator.altitude_mapping = AltitudeMapping::quadratic;
    for (const MultiscatteringLutSpec& spec : {MultiscatteringLutSpec{12, 10, 16, 12}, terminator}) {
      const Texture ms = bake_multiscattering_lut(atm, t, spec, {});
      const MultiscatteringMapping mapping = multiscattering_mapping_of(ms);
      // Radii below the ground to above the top, sun cosines past [-1, 1],
      // dense around the horizon; 4 k + 3 points, so the last group of 2 or
      // 4 lanes is short.
      const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
      std::vector<double> r, mu_s;
      for (int i = 0; i < 23; ++i)
        for (int j = 0; j < 41; ++j) {
          r.push_back(rb - 10.0 + (rt - rb + 30.0) * std::pow(i / 22.0, 2.0));
          const double x = -1.0 + 2.0 * j / 40.0;
          mu_s.push_back(1.1 * x * std::abs(x));
        }
      const size_t n = r.size();
      for (const Texture* msp : {&ms, static_cast<const Texture*>(nullptr)}) {
        std::vector<glm::dvec3> sun_lanes(n), ms_lanes(n, glm::dvec3(-1.0)), sun_one(n),
            ms_one(n, glm::dvec3(-1.0));
        read_sun_and_psi_ms(atm, t, msp, mapping, r.data(), mu_s.data(), n, sun_lanes.data(),
                            ms_lanes.data());
        size_t lit = 0, shadowed = 0;
        for (size_t k = 0; k < n; ++k) {
          sun_one[k] = lookup_sun_transmittance(t, atm, r[k], mu_s[k]);
          if (msp) ms_one[k] = lookup_multiscattering(ms, mapping, atm, r[k], mu_s[k]);
          (sun_one[k] == glm::dvec3(0.0) ? shadowed : lit) += 1;
        }
        EXPECT_TRUE(same_bits(sun_lanes, sun_one));
        EXPECT_TRUE(same_bits(ms_lanes, ms_one));  // untouched (-1) without a table
        EXPECT_GT(lit, n / 4);  // both sides of the horizon are read
        EXPECT_GT(shadowed, n / 20);
      }
    }
  }
}

// Cosines across [-1, 1] with the edges, values past them and an odd count
// (a short last group of 2 or 4 lanes).
std::vector<double> batch_cosines(double lowest) {
  std::vector<double> mu = {-1.5, -1.0, -0.0, 0.0, 1.0, 1.5, lowest, std::nextafter(lowest, 0.0)};
  for (int i = 0; i < 301; ++i) mu.push_back(-1.0 + 2.0 * i / 300.0);
  return mu;
}

TEST_P(KernelsOnEachTarget, MuSTapsAreOneAtATime) {
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere()})
    for (const ScatteringShape& shape :
         {ScatteringShape{16, 64, 16, 4, kBrunetonMuSMin}, ScatteringShape{}, ScatteringShape{4, 8, 7, 2, 0.0}}) {
      const MuSAxis axis(atm, shape);
      const std::vector<double> mu_s = batch_cosines(shape.mu_s_min);
      std::vector<int> i0(mu_s.size());
      std::vector<double> w(mu_s.size());
      axis.taps(mu_s.data(), int(mu_s.size()), i0.data(), w.data());
      for (size_t k = 0; k < mu_s.size(); ++k) {
        const AxisTap t = axis.tap(mu_s[k]);
        ASSERT_EQ(i0[k], t.i0) << mu_s[k];
        ASSERT_EQ(w[k], t.w) << mu_s[k];  // bit for bit
      }
    }
}

TEST_P(KernelsOnEachTarget, ManySunsAreOneSunAtATime) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture lut = bake_transmittance_lut(atm, TransmittanceLutSpec{}, BakeContext{});
  const TransmittanceReader reader(lut, atm);
  const double rb = atm.bottom_radius_m;
  std::vector<double> mu_s, nu;
  for (int i = 0; i < 37; ++i) {
    mu_s.push_back(-0.3 + 1.3 * i / 36.0);
    nu.push_back(std::cos(0.17 * i));
  }
  SingleScatteringRay ray;
  SingleScatteringRay::Scratch scratch;
  std::vector<SingleScattering> many(mu_s.size());
  for (double h : {0.0, 2e3, 30e3}) {
    for (double mu : {0.9, 0.05, -0.05, -0.8}) {
      const double r = rb + h;
      ray.prepare(atm, reader, r, mu, ray_intersects_ground(rb, r, mu), 30);
      ray.at_suns(reader, mu_s.data(), nu.data(), int(mu_s.size()), atm.sun_illuminance,
                  many.data(), scratch);
      for (size_t k = 0; k < mu_s.size(); ++k) {
        const SingleScattering one = ray.at_sun(reader, mu_s[k], nu[k], atm.sun_illuminance);
        ASSERT_EQ(many[k].rayleigh, one.rayleigh) << h << " " << mu << " " << k;
        ASSERT_EQ(many[k].mie, one.mie) << h << " " << mu << " " << k;
      }
    }
  }
}

// A row of 13 texels (the loops' groups of 4 and 8 both padded), read from
// a slice of made-up values: every texel's sum equals SunCosineTapsFloat::tap and
// the bilinear read of both nu slices one texel at a time, bit for bit, the
// one-slice texels' read included.
struct Row {
  static constexpr int kN = 13, kPadded = 16, kSingle = 8, kMuS = 9, kNu = 3;
  std::vector<double> mu_s, nu;
  std::vector<int> nu_i0, nu_i1, at0, at1;
  std::vector<float> nu_w, lw;
  std::vector<Rgb4> slice;
  Row()
      : mu_s(kPadded), nu(kPadded), nu_i0(kPadded), nu_i1(kPadded), at0(kPadded), at1(kPadded),
        nu_w(kPadded), lw(kPadded), slice(kMuS * kNu) {
    // Texels 0-7 read one nu slice (NodeRow::single), 8-12 two.
    for (int x = 0; x < kN; ++x) {
      mu_s[x] = -0.3 + 1.3 * x / (kN - 1);
      nu[x] = std::sin(0.7 * x);
      nu_i0[x] = (x % (kNu - 1)) * kMuS;
      nu_i1[x] = x < kSingle ? nu_i0[x] : nu_i0[x] + kMuS;
      nu_w[x] = x < kSingle ? 0.0f : float(0.1 + 0.06 * x);
    }
    for (size_t t = 0; t < slice.size(); ++t)
      slice[t] = Rgb4{{float(1.0 + t), float(std::sqrt(1.0 + t)), float(1.0 / (1.0 + t)), 0.0f}};
  }
  NodeRow node(double s) {
    return NodeRow{6.37e6,       s,          1.0 / 6.372e6, kSingle,    mu_s.data(), nu.data(),
                   nu_i0.data(), nu_i1.data(), nu_w.data(), at0.data(), at1.data(), lw.data()};
  }
};

std::vector<Rgb4> node_sums(Row& row, const SunCosineTapsFloat& taps) {
  std::vector<Rgb4> sum(Row::kPadded);
  const Rgb4 wS{{0.5f, 0.25f, 0.125f, 0.0f}};
  for (double s : {0.0, 3e4, 2e5})
    add_node_slice_reads(row.node(s), taps, row.slice.data(), wS, Row::kPadded, sum.data());
  return sum;
}

TEST_P(KernelsOnEachTarget, NodeSliceReadsAreOneTexelAtATime) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SunCosineTapsFloat taps(MuSAxis(atm, ScatteringShape{4, 8, Row::kMuS, Row::kNu, -0.2}).constants());
  Row row;
  std::vector<Rgb4> expected(Row::kN);
  for (double s : {0.0, 3e4, 2e5})
    for (int x = 0; x < Row::kN; ++x) {
      const NodeRow q = row.node(s);
      int i0 = 0;
      float lw = 0.0f;
      taps.tap((q.r * q.mu_s[x] + q.s * q.nu[x]) * q.inv_r_i, i0, lw);
      const Rgb4* s0 = &row.slice[size_t(i0 + q.nu_i0[x])];
      const Rgb4* s1 = &row.slice[size_t(i0 + q.nu_i1[x])];
      const float nw = q.nu_w[x], wS[3] = {0.5f, 0.25f, 0.125f};
      for (int c = 0; c < 3; ++c) {
        const float a = (1.0f - lw) * s0[0].v[c] + lw * s0[1].v[c];
        const float b = (1.0f - lw) * s1[0].v[c] + lw * s1[1].v[c];
        expected[size_t(x)].v[c] += wS[c] * ((1.0f - nw) * a + nw * b);
      }
    }
  const std::vector<Rgb4> sum = node_sums(row, taps);
  for (int x = 0; x < Row::kN; ++x)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(sum[size_t(x)].v[c], expected[size_t(x)].v[c]) << x;
}

// A row of 13 texels over a made-up density in the sun's frame (2 r
// texels x 3 nu slices x 9 mu_s texels x 5 cos_phi texels), at nodes of
// several distances and view cosines: every texel's sum equals
// sun_frame_tap and sun_frame_read one texel at a time, bit for bit, the
// texels of one nu slice (0-7) and of two (8-12), the view along the sun
// (nu = 1: no azimuth) and cos_phi at both ends included.
TEST_P(KernelsOnEachTarget, SunFrameReadsAreOneTexelAtATime) {
  constexpr int kN = 13, kArrays = 32, kSingle = 8, kMuS = 9, kNu = 3, kPhi = 5;
  const Atmosphere atm = fixtures::earth_atmosphere();
  const SunCosineTapsFloat taps(MuSAxis(atm, ScatteringShape{4, 8, kMuS, kNu, -0.2}).constants());
  std::vector<double> mu_s(kArrays), nu(kArrays);
  std::vector<float> nu_f(kArrays), sin_nu(kArrays), nu_w(kArrays), lw(kArrays), pw(kArrays);
  std::vector<int> nu_i0(kArrays), nu_i1(kArrays), at0(kArrays), at1(kArrays);
  for (int x = 0; x < kN; ++x) {
    mu_s[x] = -0.3 + 1.3 * x / (kN - 1);
    nu[x] = x == 3 ? 1.0 : std::sin(0.7 * x);
    nu_f[x] = float(nu[x]);
    sin_nu[x] = float(std::sqrt(1.0 - nu[x] * nu[x]));
    nu_i0[x] = (x % (kNu - 1)) * kMuS;
    nu_i1[x] = x < kSingle ? nu_i0[x] : nu_i0[x] + kMuS;
    nu_w[x] = x < kSingle ? 0.0f : float(0.1 + 0.06 * x);
  }
  std::vector<Rgb4> table(2 * kNu * kMuS * kPhi);
  for (size_t t = 0; t < table.size(); ++t)
    table[t] = Rgb4{{float(1.0 + t), float(std::sqrt(1.0 + t)), float(1.0 / (1.0 + t)), 0.0f}};
  const Rgb4* r0 = table.data();
  const Rgb4* r1 = table.data() + kNu * kMuS * kPhi;
  const Rgb4 wS{{0.5f, 0.25f, 0.125f, 0.0f}};
  std::vector<Rgb4> sum(kArrays), expected(kN);
  for (double s : {0.0, 3e4, 2e5})
    for (float mu_i : {-1.0f, -0.3f, 0.2f, 0.9f, 1.0f}) {
      const SunFrameNode q{6.37e6,       s,           1.0 / 6.372e6, mu_i,        kPhi,
                           kSingle,      mu_s.data(), nu.data(),     nu_f.data(), sin_nu.data(),
                           nu_i0.data(), nu_i1.data(), nu_w.data(),  at0.data(),  at1.data(),
                           lw.data(),    pw.data()};
      const float rw = float(s / 3e5);
      add_sun_frame_reads(q, taps, r0, r1, rw, wS, 16, sum.data());
      std::vector<int> one_at0(kN), one_at1(kN);
      std::vector<float> one_lw(kN), one_pw(kN);
      for (int x = 0; x < kN; ++x)
        sun_frame_tap(q, taps, x, one_at0[x], one_at1[x], one_lw[x], one_pw[x]);
      const SunFrameNode one{q.r,          q.s,           q.inv_r_i,      q.mu_i,        kPhi,
                             kSingle,      mu_s.data(),   nu.data(),      nu_f.data(),   sin_nu.data(),
                             nu_i0.data(), nu_i1.data(),  nu_w.data(),    one_at0.data(), one_at1.data(),
                             one_lw.data(), one_pw.data()};
      for (int x = 0; x < kN; ++x) {
        const Rgb4 read = sun_frame_read(one, r0, r1, rw, x);
        for (int c = 0; c < 4; ++c) expected[size_t(x)].v[c] += wS.v[c] * read.v[c];
      }
    }
  for (int x = 0; x < kN; ++x)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(sum[size_t(x)].v[c], expected[size_t(x)].v[c]) << x;
}

// Rows of 1, 2 and 5 texels (a last texel after whole vectors of 8 lanes)
// blended with weights that round: every float as the one-texel sum.
TEST_P(KernelsOnEachTarget, RowBlendIsOneTexelAtATime) {
  for (int n : {1, 2, 5}) {
    std::vector<Rgb4> rows[4];
    std::vector<Rgb4> out(static_cast<size_t>(n));
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < n; ++i)
        rows[k].push_back(Rgb4{{float(std::sin(1.0 + i + k)), float(1.0 / (3.0 + i * k)),
                                float(std::sqrt(2.0 + i)), 0.0f}});
    const Rgb4* const r[4] = {rows[0].data(), rows[1].data(), rows[2].data(), rows[3].data()};
    const float w[4] = {0.1f, 0.7f / 3.0f, 0.3f, 1.0f / 7.0f};
    blend_rows(r, w, n, out.data());
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(out[size_t(i)].v[c], (w[0] * r[0][i].v[c] + w[1] * r[1][i].v[c]) +
                                           (w[2] * r[2][i].v[c] + w[3] * r[3][i].v[c]))
            << n << " " << i << " " << c;
  }
}

// The transmittance quadrature's node altitudes against the one-value
// formula, bit for bit, and against radius_after (the same radius up to
// rounding): rays up, down, grazing and through the perigee, n from 1 to 19
// so that every target has a short tail.
TEST_P(KernelsOnEachTarget, NodeAltitudesAreOneNodeAtATime) {
  const double rb = 6360e3, r = 6360e3 + 12e3;
  for (double mu : {-1.0, -0.3, -0.02, 0.0, 0.4, 1.0})
    for (size_t n : {size_t(1), size_t(3), size_t(8), size_t(19)}) {
      const double from_perigee = r * mu, p2 = r * r * std::max(0.0, (1.0 - mu) * (1.0 + mu));
      std::vector<double> s(n), one(n);
      for (size_t j = 0; j < n; ++j) {
        s[j] = 900e3 * std::pow(double(j) / double(n), 1.25);
        one[j] = node_altitude_from_perigee(s[j], from_perigee, p2, rb);
        ASSERT_NEAR(one[j], radius_after(r, mu, s[j]) - rb, 1e-6) << mu << " " << s[j];
      }
      altitudes_from_perigee(s.data(), n, from_perigee, p2, rb);
      EXPECT_EQ(std::memcmp(s.data(), one.data(), n * sizeof(double)), 0) << mu << " " << n;
    }
}

// The density's Mie loop against one pair at a time (pair j into lane j % 8
// of each sum, the lanes added in double): 5 and 6 zenith bands (25 and 36
// pairs, padded to 32 and 40), both phase functions, forward and backward
// views.
TEST_P(KernelsOnEachTarget, MieSumsAreOnePairAtATime) {
  for (int bands : {5, 6})
    for (PhaseKind kind : {PhaseKind::cornette_shanks, PhaseKind::henyey_greenstein}) {
      const SphereGrid grid = sphere_grid(bands);
      MieBatch batch(grid);
      std::vector<glm::dvec3> L(grid.directions.size());
      for (size_t i = 0; i < L.size(); ++i)
        L[i] = glm::dvec3(1.0 + std::sin(0.3 * i), 0.5, 1.0 / (1.0 + i));
      batch.set_field(L);
      ScatteringPhases phases;
      phases.mie_g = 0.8;
      phases.mie_phase = kind;
      const MieKernel k(phases);
      for (const glm::dvec3 v : {glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(0.6, 0.0, -0.8),
                                 glm::normalize(glm::dvec3(0.3, 0.5, 0.2))}) {
        double out[4];
        batch.sums(k, v, out);
        float lanes[4][MieBatch::kLanes] = {};
        const float vx = float(v.x), vy = float(v.y), vz = float(v.z);
        const float a = float(k.a), b = float(k.b), cs = k.cornette_shanks ? 1.0f : 0.0f;
        for (size_t j = 0; j < batch.n; ++j) {
          const float in_plane = vx * batch.x[j] + vz * batch.z[j], across = vy * batch.y[j];
          const float cp = in_plane + across, cm = in_plane - across;
          const float wp = a + b * std::max(1.0f - cp, 0.0f), wm = a + b * std::max(1.0f - cm, 0.0f);
          const float qp = wp * std::sqrt(wp), qm = wm * std::sqrt(wm);
          const float p = ((1.0f + cs * (cp * cp)) * qm + (1.0f + cs * (cm * cm)) * qp) / (qp * qm);
          for (int c = 0; c < 4; ++c) lanes[c][j % 8] += p * batch.blocks[MieBatch::field(c, j)];
        }
        for (int c = 0; c < 4; ++c) {
          const float* s = lanes[c];
          const double expected = ((double(s[0]) + s[1]) + (double(s[2]) + s[3])) +
                                  ((double(s[4]) + s[5]) + (double(s[6]) + s[7]));
          ASSERT_EQ(out[c], expected) << bands << " " << int(kind) << " " << c;
        }
      }
    }
}

SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET();

}  // namespace
}  // namespace skybake

// The multiple-scattering pass's node loop (atmosphere/kernels/node_slice_reads.hpp): its
// single-precision mu_s taps against the double mapping, and its AVX2 and
// SSE2 loops against one texel at a time.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/kernels/node_slice_reads.hpp"
#include "core/simd_switches.hpp"
#include "support/test_atmospheres.hpp"
#include "support/wide_vectors_as.hpp"

namespace skybake {
namespace {

// Cosines across [-1, 1] in fine steps, the edges and values past them.
std::vector<double> cosines(double mu_s_min) {
  std::vector<double> mu = {-1.5, -1.0, -0.0, 0.0, 1.0, 1.5, mu_s_min, std::nextafter(mu_s_min, 0.0),
                            std::nextafter(1.0, 0.0)};
  for (int i = 0; i <= 20000; ++i) mu.push_back(-1.0 + 2.0 * i / 20000.0);
  return mu;
}

// The texel coordinate i0 + w of a tap.
TEST(SunCosineTapsFloat, WithinAFortiethOfAThousandthOfATexelOfTheDoubleMapping) {
  Atmosphere thick = fixtures::earth_atmosphere();
  // A shell 0.8 Rb thick: span = H - d_min < d_min, so k2 < 0 in the mapping.
  thick.top_radius_m = 1.8 * thick.bottom_radius_m;
  for (const Atmosphere& atm :
       {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), thick})
    for (const ScatteringShape& shape :
         {ScatteringShape{}, ScatteringShape{8, 32, 64, 4, -0.5}, ScatteringShape{4, 8, 7, 2, 0.0}}) {
      const MuSAxis axis(atm, shape);
      const SunCosineTapsFloat taps(axis.constants());
      for (double mu_s : cosines(shape.mu_s_min)) {
        const AxisTap exact = axis.tap(mu_s);
        int i0 = -1;
        float w = -1.0f;
        taps.tap(mu_s, i0, w);
        ASSERT_GE(i0, 0);
        ASSERT_LE(i0, shape.mu_s_size - 2);
        ASSERT_GE(w, 0.0f);
        ASSERT_LE(w, 1.0f);
        ASSERT_NEAR(i0 + double(w), exact.i0 + exact.w, 2.5e-5)
            << "mu_s " << mu_s << " top " << atm.top_radius_m << " mu_s_min " << shape.mu_s_min;
      }
    }
}

// A row of 13 texels (the loops' groups of 4 and 8 both padded), read from
// a slice of made-up values: every texel's sum equals SunCosineTapsFloat::tap and
// the bilinear read of both nu slices one texel at a time, bit for bit,
// AVX-512, AVX2 and SSE2, the one-slice texels' read included.
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

// wide: 0 SSE2, 1 AVX2, 2 AVX-512 where the CPU has them.
std::vector<Rgb4> node_sums(Row& row, const SunCosineTapsFloat& taps, int wide) {
  const test::WideVectorsAs as(wide > 0);
  const test::WidestVectorsAs widest(wide > 1);
  std::vector<Rgb4> sum(Row::kPadded);
  const Rgb4 wS{{0.5f, 0.25f, 0.125f, 0.0f}};
  for (double s : {0.0, 3e4, 2e5})
    add_node_slice_reads(row.node(s), taps, row.slice.data(), wS, Row::kPadded, sum.data());
  return sum;
}

TEST(NodeSliceReads, LoopsEqualOneTexelAtATime) {
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
  for (int wide : {0, 1, 2}) {
    const std::vector<Rgb4> sum = node_sums(row, taps, wide);
    for (int x = 0; x < Row::kN; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(sum[size_t(x)].v[c], expected[size_t(x)].v[c]) << "wide " << wide << " texel " << x;
  }
}

}  // namespace
}  // namespace skybake

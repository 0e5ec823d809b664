// The multiple-scattering point rule's per-segment terms four segments at a
// time (verify/ring_segments.hpp) against the one-value loop: the same
// bits, on rays of the record's rule through Earth, the tiny planet and
// Earth under 1000x Rayleigh (optically thick segments), with segments of
// zero extinction and a remainder of fewer than four.
#include "verify/ring_segments.hpp"

#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "core/simd_switches.hpp"
#include "support/test_atmospheres.hpp"
#include "support/wide_vectors_as.hpp"

namespace skybake {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(RingSegments, FourAtATimeAreTheOneValueTermsBitForBit) {
  {
    const test::WideVectorsAs probe(true);
    if (!avx2_enabled()) GTEST_SKIP() << "this CPU has no AVX2: only the one-value loop runs";
  }
  Atmosphere dense = fixtures::earth_atmosphere();
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  size_t thick = 0, thin = 0;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense}) {
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    for (double r : {rb + 1.0, rb + 0.4 * (rt - rb)})
      for (double mu : {-0.9, -0.01, 0.05, 0.7}) {
        const bool ground = ray_intersects_ground(rb, r, mu);
        const double length = distance_to_nearest_boundary(rb, rt, r, mu, ground);
        const size_t n = 31;  // 7 groups of four and 3 left
        std::vector<double> ends(n + 1), expm1s(4 * n);
        std::vector<glm::dvec3> extinction(n);
        for (size_t i = 0; i <= n; ++i) ends[i] = length * std::pow(double(i) / n, 2.0);
        for (size_t i = 0; i < n; ++i) {
          const double dt = ends[i + 1] - ends[i];
          const double h = radius_after(r, mu, 0.5 * (ends[i] + ends[i + 1])) - rb;
          extinction[i] = i % 9 == 4 ? glm::dvec3(0.0) : extinction_at(atm, std::max(h, 0.0));
          const glm::dvec3& e = extinction[i];
          for (int c = 0; c < 3; ++c) expm1s[4 * i + c] = std::expm1(-e[c] * dt);
          const double x = (e.x + e.y + e.z) / 3.0 * dt;
          expm1s[4 * i + 3] = std::expm1(x);
          (x < 1e-4 ? thin : thick) += 1;
        }
        RingSegmentTerms one, wide;
        {
          const test::WideVectorsAs as(false);
          ring_segment_terms(ends.data(), n, extinction.data(), expm1s.data(), r, mu, rb, one);
        }
        {
          const test::WideVectorsAs as(true);
          ring_segment_terms(ends.data(), n, extinction.data(), expm1s.data(), r, mu, rb, wide);
        }
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(one.weight[c], wide.weight[c]));
        EXPECT_TRUE(same_bits(one.lit_at, wide.lit_at));
        EXPECT_TRUE(same_bits(one.lit_radius, wide.lit_radius));
        EXPECT_TRUE(same_bits(one.inverse_radius, wide.inverse_radius));
        // The one-value terms are segment_weights' and the centroid's.
        for (size_t i = 0; i < n; ++i) {
          if (extinction[i] == glm::dvec3(0.0)) continue;
          const double dt = ends[i + 1] - ends[i];
          EXPECT_NEAR(one.weight[0][i], -std::expm1(-extinction[i].x * dt) / extinction[i].x,
                      1e-15 * dt);
          EXPECT_GE(one.lit_at[i], ends[i]);
          EXPECT_LE(one.lit_at[i], ends[i + 1]);
        }
      }
  }
  EXPECT_GT(thick, 20u);  // both branches of weight_centroid are taken
  EXPECT_GT(thin, 20u);
}

}  // namespace
}  // namespace skybake

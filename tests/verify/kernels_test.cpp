// The kernels of the error records' references on every SIMD target
// against the one-value functions, bit for bit: the multiple-scattering
// record's ring sums (verify/kernels/ring_sun_sums.hpp) against
// transmittance_at_radius, then lookup_sun_transmittance per azimuth, and
// its per-segment terms (verify/kernels/ring_segments.hpp) against
// ring_segment_term.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "support/simd_targets.hpp"
#include "support/test_atmospheres.hpp"
#include "verify/kernels/ring_segments.hpp"
#include "verify/kernels/ring_sun_sums.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

TEST_P(KernelsOnEachTarget, RingSunSumsAreTheOneValueSums) {
  Atmosphere dense = fixtures::earth_atmosphere();  // the stiff extreme case: reads underflow
  for (MediumComponent& c : dense.components)
    if (c.name == "rayleigh") c.scattering_per_m *= 1000.0;
  for (const Atmosphere& atm : {fixtures::earth_atmosphere(), fixtures::tiny_planet_atmosphere(), dense}) {
    const Texture lut = bake_transmittance_lut(atm, {64, 32, 16}, {});
    const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
    // Samples from the ground to past the top (clamped), at distances along
    // rays from points at several heights, suns on both sides of the
    // horizon; 4 k + 3 samples, so the last group of 2 or 4 lanes is short.
    const size_t n = 203;
    std::vector<double> radii(n), distances(n), inverse(n);
    for (size_t i = 0; i < n; ++i) {
      radii[i] = rb + (rt - rb) * 1.02 * std::pow(double(i) / (n - 1), 2.0);
      distances[i] = (rt - rb) * 3.0 * std::fmod(0.618 * double(i), 1.0);
      inverse[i] = 1.0 / radii[i];
    }
    size_t lit = 0, dark = 0;
    for (double r0 : {rb + 10.0, rb + 0.3 * (rt - rb), rt})
      for (double mu_s : {-0.4, -0.02, 0.1, 0.9}) {
        const double cosines[4] = {0.92 * mu_s - 0.3, 0.38 * mu_s + 0.1, -0.38 * mu_s, -0.92 * mu_s};
        const double height = r0 * mu_s;
        std::vector<glm::dvec3> wide_sums(n, glm::dvec3(-1.0)), one(n);
        ring_sun_sums(lut, atm, radii.data(), distances.data(), inverse.data(), n, height,
                      cosines, 4, wide_sums.data());
        for (size_t i = 0; i < n; ++i) {
          const TransmittanceAtRadius at = transmittance_at_radius(lut, atm, radii[i]);
          glm::dvec3 sum(0.0);
          for (double c : cosines) {
            const glm::dvec3 t =
                lookup_sun_transmittance(lut, at, rb, (height + distances[i] * c) * inverse[i]);
            sum += t;
            (t == glm::dvec3(0.0) ? dark : lit) += 1;
          }
          one[i] = sum;
        }
        EXPECT_EQ(std::memcmp(one.data(), wide_sums.data(), n * sizeof(one[0])), 0)
            << r0 << " " << mu_s;
      }
    EXPECT_GT(lit, 1000u);  // both sides of the horizon are summed
    EXPECT_GT(dark, 100u);
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The multiple-scattering point rule's per-segment terms
// (verify/kernels/ring_segments.hpp) against one segment at a time, on rays
// of the record's rule through Earth, the tiny planet and Earth under 1000x
// Rayleigh (optically thick segments), with segments of zero extinction.
TEST_P(KernelsOnEachTarget, RingSegmentTermsAreOneSegmentAtATime) {
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
        const size_t n = 31;  // whole vectors of 2, 4 and 8 lanes and a rest
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
        ring_segment_terms(ends.data(), n, extinction.data(), expm1s.data(), r, mu, rb, wide);
        for (std::vector<double>* v : {&one.weight[0], &one.weight[1], &one.weight[2],
                                       &one.lit_at, &one.lit_radius, &one.inverse_radius})
          v->resize(n);
        for (size_t i = 0; i < n; ++i)
          ring_segment_term(ends.data(), i, extinction.data(), expm1s.data(), r, mu, rb, one);
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

SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET();

}  // namespace
}  // namespace skybake

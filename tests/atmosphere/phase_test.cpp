// Tests of the phase functions (atmosphere/phase.hpp): normalisation over the
// sphere, closed-form values, the forward peak and symmetry in g.
#include "atmosphere/phase.hpp"

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// Integral over the sphere of a function of cos(theta) alone:
//   int_{4 pi} p = 2 pi int_{-1}^{1} p(u) du.
// Strongly peaked lobes (g = 0.999: width ~ (1 - g)^2 in u) need nodes near
// u = +-1, so each half is mapped u = +-(1 - t^3), du = 3 t^2 dt, which
// packs the nodes toward the poles, and integrated with composite 3-point
// Gauss-Legendre in t.
double integrate_over_sphere(const std::function<double(double)>& p) {
  const int segments = 4000;
  const double node = std::sqrt(0.6), nodes[3] = {-node, 0.0, node};
  const double weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double sum = 0.0;
  for (double pole : {1.0, -1.0}) {
    for (int i = 0; i < segments; ++i) {
      const double mid = (i + 0.5) / segments, half = 0.5 / segments;
      for (int k = 0; k < 3; ++k) {
        const double t = mid + half * nodes[k];
        const double u = pole * (1.0 - t * t * t);
        sum += half * weights[k] * 3.0 * t * t * p(u);
      }
    }
  }
  return 2.0 * kPi * sum;
}

TEST(Phase, IsotropicIntegratesToOne) {
  EXPECT_NEAR(integrate_over_sphere([](double) { return isotropic_phase(); }), 1.0, 1e-12);
}

TEST(Phase, RayleighIntegratesToOne) {
  EXPECT_NEAR(integrate_over_sphere(rayleigh_phase), 1.0, 1e-10);
}

TEST(Phase, RayleighClosedFormValues) {
  // 3 (1 + c^2) / (16 pi): 3/(16 pi) at 90 degrees, twice that forward and back.
  EXPECT_NEAR(rayleigh_phase(0.0), 3.0 / (16.0 * kPi), 1e-15);
  EXPECT_NEAR(rayleigh_phase(1.0), 6.0 / (16.0 * kPi), 1e-15);
  EXPECT_NEAR(rayleigh_phase(-1.0), 6.0 / (16.0 * kPi), 1e-15);
}

class PhaseG : public ::testing::TestWithParam<double> {};

TEST_P(PhaseG, CornetteShanksIntegratesToOne) {
  const double g = GetParam();
  EXPECT_NEAR(integrate_over_sphere([g](double u) { return cornette_shanks_phase(u, g); }), 1.0,
              1e-6)
      << "g " << g;
}

TEST_P(PhaseG, HenyeyGreensteinIntegratesToOne) {
  const double g = GetParam();
  EXPECT_NEAR(integrate_over_sphere([g](double u) { return henyey_greenstein_phase(u, g); }), 1.0,
              1e-6)
      << "g " << g;
}

TEST_P(PhaseG, MirrorSymmetryInG) {
  // Both depend on g c only through 1 + g^2 - 2 g c (and CS on c^2), so
  // p(c, -g) = p(-c, g).
  const double g = GetParam();
  for (double c = -1.0; c <= 1.0; c += 0.25) {
    EXPECT_DOUBLE_EQ(cornette_shanks_phase(c, -g), cornette_shanks_phase(-c, g));
    EXPECT_DOUBLE_EQ(henyey_greenstein_phase(c, -g), henyey_greenstein_phase(-c, g));
  }
}

INSTANTIATE_TEST_SUITE_P(Asymmetries, PhaseG,
                         ::testing::Values(0.0, 0.3, 0.76, 0.8, 0.99, 0.999, -0.5, -0.99));

TEST(Phase, CornetteShanksIsRayleighAtZeroG) {
  for (double c = -1.0; c <= 1.0; c += 0.125)
    EXPECT_NEAR(cornette_shanks_phase(c, 0.0), rayleigh_phase(c), 1e-16);
}

TEST(Phase, HenyeyGreensteinClosedFormAtThePoles) {
  // c = 1: (1 - g^2) / (4 pi (1 - g)^3) = (1 + g) / (4 pi (1 - g)^2);
  // c = -1: (1 - g) / (4 pi (1 + g)^2).
  const double g = 0.8;
  EXPECT_NEAR(henyey_greenstein_phase(1.0, g), 1.8 / (4.0 * kPi * 0.04), 1e-12);
  EXPECT_NEAR(henyey_greenstein_phase(-1.0, g), 0.2 / (4.0 * kPi * 3.24), 1e-12);
  EXPECT_NEAR(henyey_greenstein_phase(0.3, 0.0), 1.0 / (4.0 * kPi), 1e-16);
}

TEST(Phase, ForwardPeakForPositiveG) {
  // With cos_theta = dot(view, to_sun), looking at the sun is c = 1: that is
  // where the Mie halo must be, and the maximum over c for g > 0.
  for (double g : {0.3, 0.8, 0.99}) {
    const double cs_peak = cornette_shanks_phase(1.0, g);
    const double hg_peak = henyey_greenstein_phase(1.0, g);
    for (double c = -1.0; c < 1.0; c += 1.0 / 64.0) {
      EXPECT_LT(cornette_shanks_phase(c, g), cs_peak) << g << " " << c;
      EXPECT_LT(henyey_greenstein_phase(c, g), hg_peak) << g << " " << c;
    }
    EXPECT_GT(cornette_shanks_phase(1.0, g), cornette_shanks_phase(-1.0, g));
  }
}

TEST(Phase, ClampsTheCosine) {
  // A rounding error past +-1 reads the pole, not a value past the peak.
  EXPECT_EQ(henyey_greenstein_phase(1.0 + 1e-12, 0.9), henyey_greenstein_phase(1.0, 0.9));
  EXPECT_EQ(rayleigh_phase(-1.0 - 1e-12), rayleigh_phase(-1.0));
}

TEST(Phase, DispatchByKind) {
  EXPECT_EQ(phase_function(PhaseKind::none, 0.8, 0.5), 0.0);
  EXPECT_EQ(phase_function(PhaseKind::rayleigh, 0.8, 0.5), rayleigh_phase(0.5));
  EXPECT_EQ(phase_function(PhaseKind::cornette_shanks, 0.8, 0.5), cornette_shanks_phase(0.5, 0.8));
  EXPECT_EQ(phase_function(PhaseKind::henyey_greenstein, 0.8, 0.5),
            henyey_greenstein_phase(0.5, 0.8));
}

}  // namespace
}  // namespace skybake

// The report's sky views as a linear function of the multiple-scattering
// table (report/psi_weights.hpp): single + weights . table reproduces the
// report's own rendering of any table, no texel darkens a view, and texels
// no view's march reaches (sun cosines near -1 while the sun is up) weigh
// nothing; the same for a table by view, and the oracle's least-squares fit
// of one renders as it promised.
#include <gtest/gtest.h>

#include <cmath>

#include "core/math.hpp"
#include "report/psi_weights.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

using fixtures::bake_sky_lut_inputs;
using fixtures::earth_atmosphere;
using fixtures::SkyLutInputs;

struct Fixture {
  Atmosphere atm = earth_atmosphere();
  SkyLutInputs luts = bake_sky_lut_inputs(atm);
  SkyRadianceCamera camera;
  std::vector<double> suns{30.0, 5.0};

  Fixture() {
    camera.altitude_m = 200.0;
    camera.position = glm::dvec3(0.0, 0.0, atm.bottom_radius_m + camera.altitude_m);
    for (double e : {5.0, 40.0})
      for (double phi : {0.3, 2.5}) {
        const double er = e * kPi / 180.0;
        camera.dirs.push_back(
            {std::cos(er) * std::cos(phi), std::cos(er) * std::sin(phi), std::sin(er)});
      }
    camera.sky.width = 32;
    camera.sky.height = 18;
    camera.sky.steps = 12;
  }
};

TEST(PsiWeights, ReproduceTheReportsRenderingOfAnyTable) {
  const Fixture f;
  const PsiWeights w =
      sky_view_psi_weights(f.atm, f.luts.transmittance, f.luts.multiscattering, f.camera, f.suns);
  ASSERT_EQ(w.views, f.suns.size() * f.camera.dirs.size());
  Texture other = f.luts.multiscattering;  // another table: texels scaled unevenly
  for (size_t i = 0; i < other.data.size(); ++i)
    other.data[i] *= float(1.0 + 0.8 * std::sin(0.7 * double(i)));
  for (const Texture* table : {&f.luts.multiscattering, static_cast<const Texture*>(&other)}) {
    const std::vector<glm::dvec3> linear = apply_psi_weights(w, *table);
    for (size_t s = 0; s < f.suns.size(); ++s) {
      const std::vector<glm::dvec3> rendered =
          render_sky_views(f.atm, f.luts.transmittance, *table, f.camera, f.suns[s]);
      for (size_t v = 0; v < rendered.size(); ++v)
        for (int c = 0; c < 3; ++c) {
          const glm::dvec3 l = linear[s * f.camera.dirs.size() + v];
          EXPECT_NEAR(l[c] / rendered[v][c], 1.0, 1e-5) << "sun " << s << " view " << v;
          // The multiple part is no small correction here: the test sees it.
          EXPECT_GT(l[c] - w.single[s * f.camera.dirs.size() + v][c], 1e-3 * l[c]);
        }
    }
  }
}

TEST(PsiWeights, NoTexelDarkensAViewAndUnreachedTexelsWeighNothing) {
  const Fixture f;
  const PsiWeights w =
      sky_view_psi_weights(f.atm, f.luts.transmittance, f.luts.multiscattering, f.camera, f.suns);
  double largest = 0.0;
  for (const glm::dvec3& x : w.weights) largest = std::max({largest, x.x, x.y, x.z});
  ASSERT_GT(largest, 0.0);
  for (size_t v = 0; v < w.views; ++v)
    for (int y = 0; y < w.height; ++y)
      for (int x = 0; x < w.width; ++x)
        for (int c = 0; c < 3; ++c) {
          // float32 layers: a texel's share can round a little below 0.
          EXPECT_GE(w.weight(v, x, y)[c], -1e-6 * largest);
          // The first columns hold mu_s near -1 (the linear mapping): no
          // point a view marches through, with the sun 5 degrees up or more,
          // has its sun that far below the horizon.
          if (x < 2) {
            EXPECT_EQ(w.weight(v, x, y)[c], 0.0) << x << " " << y;
          }
        }
}

// A table by view (docs/reference.md "Psi_ms by view"), 8 x 8 (every other
// texel of the isotropic one) with 2 nu and 2 zenith slices after the
// isotropic one, uneven values.
Texture view_table(const Texture& isotropic) {
  Texture t(8, 8, 5, 1, {"R", "G", "B"});
  t.metadata = isotropic.metadata;
  set_meta(t.metadata, "nu_slices", 2);
  set_meta(t.metadata, "zenith_slices", 2);
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c)
          t.texel(x, y, z)[c] =
              isotropic.at(2 * x, 2 * y, 0, 0, c) *
              float(0.6 + 0.3 * z + 0.2 * std::sin(1.3 * double((z * 8 + y) * 8 + x) + c));
  return t;
}

TEST(PsiWeights, ATableByViewIsLinearTooAndItsIsotropicSliceWeighsNothing) {
  const Fixture f;
  const Texture table = view_table(f.luts.multiscattering);
  const PsiWeights w = sky_view_psi_weights(f.atm, f.luts.transmittance, table, f.camera, f.suns);
  ASSERT_EQ(w.texels(), size_t(8 * 8 * 5));
  const std::vector<glm::dvec3> linear = apply_psi_weights(w, table);
  for (size_t s = 0; s < f.suns.size(); ++s) {
    const std::vector<glm::dvec3> rendered =
        render_sky_views(f.atm, f.luts.transmittance, table, f.camera, f.suns[s]);
    for (size_t v = 0; v < rendered.size(); ++v)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(linear[s * f.camera.dirs.size() + v][c] / rendered[v][c], 1.0, 1e-5);
  }
  double sum_a = 0.0;
  for (size_t v = 0; v < w.views; ++v)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        EXPECT_EQ(w.weight(v, x, y, 0), glm::dvec3(0.0));  // the views read slices 1..4
        sum_a += w.weight(v, x, y, 1).x + w.weight(v, x, y, 2).x;
      }
  EXPECT_GT(sum_a, 0.0);
}

// The oracle (bench/psi_oracle.py) at a small size: its least-squares
// table, found from the weights alone, rendered by the report's own code
// gives the radiance the fit promised. Here the views' targets are those of
// another table of the same form, which the fit must reach.
TEST(PsiWeights, TheOraclesFitOfATableByViewRendersAsPromised) {
  const Fixture f;
  const Texture start = view_table(f.luts.multiscattering);
  Texture truth = start;
  for (size_t i = 0; i < truth.data.size(); ++i)
    truth.data[i] *= float(1.0 + 0.5 * std::cos(0.9 * double(i)));
  const PsiWeights w = sky_view_psi_weights(f.atm, f.luts.transmittance, start, f.camera, f.suns);
  const std::vector<glm::dvec3> target = apply_psi_weights(w, truth);
  const std::vector<glm::dvec3> before = apply_psi_weights(w, start);
  // Per channel, the least change of the table that meets every view:
  // x = x0 + A^T (A A^T)^-1 (b - A x0 - s), A the views x texels weights.
  Texture fit = start;
  const size_t n = w.views, k = w.texels();
  for (int c = 0; c < 3; ++c) {
    std::vector<double> m(n * n, 0.0), r(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      r[i] = target[i][c] - before[i][c];
      for (size_t j = 0; j < n; ++j)
        for (size_t t = 0; t < k; ++t) m[i * n + j] += w.weights[i * k + t][c] * w.weights[j * k + t][c];
    }
    for (size_t p = 0; p < n; ++p)  // Gauss-Jordan: m is small and positive definite
      for (size_t i = 0; i < n; ++i) {
        if (i == p) continue;
        const double q = m[i * n + p] / m[p * n + p];
        for (size_t j = 0; j < n; ++j) m[i * n + j] -= q * m[p * n + j];
        r[i] -= q * r[p];
      }
    for (size_t t = 0; t < k; ++t) {
      double dx = 0.0;
      for (size_t i = 0; i < n; ++i) dx += w.weights[i * k + t][c] * r[i] / m[i * n + i];
      fit.data[t * 3 + size_t(c)] += float(dx);
    }
  }
  double start_off = 0.0;
  for (size_t s = 0; s < f.suns.size(); ++s) {
    const std::vector<glm::dvec3> rendered =
        render_sky_views(f.atm, f.luts.transmittance, fit, f.camera, f.suns[s]);
    for (size_t v = 0; v < rendered.size(); ++v) {
      const size_t i = s * f.camera.dirs.size() + v;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(rendered[v][c] / target[i][c], 1.0, 1e-4) << i << " " << c;
        start_off += std::abs(before[i][c] / target[i][c] - 1.0) / double(3 * n);
      }
    }
  }
  EXPECT_GT(start_off, 1e-2);  // the start was far from the targets: the fit did the work
}

}  // namespace
}  // namespace skybake

// The report's sky views as a linear function of the multiple-scattering
// table (report/psi_weights.hpp): single + weights . table reproduces the
// report's own rendering of any table, no texel darkens a view, and texels
// no view's march reaches (sun cosines near -1 while the sun is up) weigh
// nothing.
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

}  // namespace
}  // namespace skybake

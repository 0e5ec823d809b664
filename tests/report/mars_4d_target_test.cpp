// Mars's 4D table against the path tracer (mars_4d_target_accuracy_test.cpp)
// cut down for the unit tier: r and mu halved (16 x 64), the report's 24
// views under a sun 20 degrees up, 4096 paths. The lobe's angular axes (64
// sun texels, 16 nu slices) against the report's old ones (32, 8) at the
// same r and mu, worst channel, the tracer's noise taken out: measured 4.0 %
// against 5.7 % (halved r and mu cost the rest: 2.8 % at full size). Bars:
// below 5 % and at least a fifth below the old axes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "reference/path_tracer.hpp"
#include "report/setup.hpp"
#include "report/sky_radiance.hpp"

namespace skybake {
namespace {

TEST(Mars4dTarget, LobeAxesCutTheErrorOnACutDownTable) {
  const Scene scene = load_scene(std::string(SKYBAKE_SOURCE_DIR) + "/presets/mars.json");
  const Atmosphere& atm = scene.atmosphere;
  const Texture lut = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  const SkyRadianceCamera cam = sky_radiance_camera(scene, SkyRadianceSetup::full());
  const SkyPathTracer tracer(atm);
  PathTracerSpec paths;
  paths.samples = 4096;
  paths.max_bounces = sky_radiance_max_bounces(atm);
  const glm::dvec3 sun = sky_radiance_sun(20.0);
  std::vector<RadianceEstimate> traced;
  for (size_t v = 0; v < cam.dirs.size(); ++v) {
    paths.seed = 3 * (cam.dirs.size() + v) + 1;  // the report's seeds for this sun
    traced.push_back(tracer.trace(cam.position, cam.dirs[v], sun, paths));
  }
  const double r = glm::length(cam.position);
  double worst[2] = {0.0, 0.0};
  for (int lobe = 0; lobe < 2; ++lobe) {
    BrunetonSpec spec;
    spec.r_size = 16, spec.mu_size = 64;
    spec.mu_s_size = lobe ? 64 : 32, spec.nu_size = lobe ? 16 : 8;
    spec.tolerance = 1e-3;
    spec.combined_mie_alpha = false;
    const BrunetonTextures t = bake_bruneton(atm, lut, spec, BakeContext{});
    std::vector<RadiancePair> pairs;
    for (size_t v = 0; v < cam.dirs.size(); ++v) {
      const glm::dvec3& dir = cam.dirs[v];
      const glm::dvec3 l = lookup_scattering(
          t.scattering, t.single_mie, t.shape, atm, r, dir.z, sun.z,
          clamp_cosine(glm::dot(dir, sun)), ray_intersects_ground(atm.bottom_radius_m, r, dir.z));
      pairs.push_back({l, traced[v].mean, traced[v].ci95, traced[v].mean});
    }
    worst[lobe] = radiance_stats(pairs)["worst"]["rel_rmse_denoised"].get<double>();
  }
  RecordProperty("worst_old_axes", fmt::format("{:.4f}", worst[0]));
  RecordProperty("worst_lobe_axes", fmt::format("{:.4f}", worst[1]));
  EXPECT_LT(worst[1], 0.05);
  EXPECT_LT(worst[1], 0.8 * worst[0]);
}

}  // namespace
}  // namespace skybake

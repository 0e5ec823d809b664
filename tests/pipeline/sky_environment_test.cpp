// sky_environment through the pipeline's writer and back through real
// readers: skybake's own KTX2 and DDS readers (the cube flags), and
// three.js's KTX2Loader under node (tests/js/ktx2_three_cube.mjs). Level 0
// read back from the float16 files against the radiance integrated directly
// along each texel's direction, the direction taken from the OpenGL
// specification's face table (sec. 8.13, table 8.19) written out here and
// the cube frame of docs/runtime.md "Sky environment" (+Y up, the sun
// toward +X), within 1% RMS; the cube's SH against sky_irradiance's
// independent Gauss-rule projection at the same view.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_environment.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/cube_map.hpp"
#include "io/dds.hpp"
#include "io/ktx2.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product.hpp"
#include "support/run.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;

struct EnvFixture {
  Atmosphere atm = fixtures::earth_atmosphere();
  Texture transmittance = bake_transmittance_lut(atm, {}, {});
  Texture multiscattering = bake_multiscattering_lut(atm, transmittance, {}, {});
  SkyIrradianceSpec irradiance_spec;
  SkyRadianceSource source = psi_ms_source(atm, transmittance, multiscattering, irradiance_spec);
};

const EnvFixture& env_fixture() {
  static const EnvFixture f;
  return f;
}

SkyEnvironmentSpec small_spec() {
  SkyEnvironmentSpec s;
  s.face = 16;
  s.views = {{1000.0, 50.0 * kDeg}};
  return s;
}

// The direction of texel (i, j) of face f of an n x n face: OpenGL 4.6
// table 8.19 solved for the direction, (sc, tc) at the texel's centre.
glm::dvec3 gl_table_direction(int f, int i, int j, int n) {
  const double sc = 2.0 * (i + 0.5) / n - 1.0, tc = 2.0 * (j + 0.5) / n - 1.0;
  const glm::dvec3 by_face[6] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc},
                                 {sc, -1, -tc}, {sc, -tc, 1},  {-sc, -tc, -1}};
  return glm::normalize(by_face[f]);
}

// Writes the cube with the pipeline's writer (KTX2 and DDS, the product's
// GGX chain), into a fresh folder; returns it.
fs::path write_environment(const Texture& level0, const std::string& group) {
  const fs::path dir = test::fresh_dir(group);
  OutputSpec spec;
  spec.product = "sky_environment";
  spec.name = "env";
  spec.size = {level0.width, level0.width};
  spec.formats = {"ktx2", "dds"};
  spec.options = nlohmann::json::object({{"product", "sky_environment"}, {"ggx_samples", 64}});
  write_outputs(level0, *find_product("sky_environment"), spec, dir);
  return dir;
}

TEST(SkyEnvironment, LevelZeroMatchesTheDirectlyIntegratedRadiance) {
  const EnvFixture& fx = env_fixture();
  const SkyEnvironmentSpec spec = small_spec();
  const Texture level0 = bake_sky_environment(fx.atm, fx.source, spec, {});
  const fs::path dir = write_environment(level0, "sky_environment_level0");
  const Ktx2Image ktx2 = read_ktx2((dir / "env.ktx2").string());
  const DdsImage dds = read_dds((dir / "env.dds").string());
  ASSERT_TRUE(ktx2.cube);
  ASSERT_TRUE(dds.cube);
  ASSERT_EQ(ktx2.mips.size(), 2u);  // 16 and 8 texels: down to 8 x 8 faces
  ASSERT_EQ(dds.mips.size(), 2u);
  const double r = fx.atm.bottom_radius_m + spec.views[0].altitude_m;
  const double theta_s = spec.views[0].sun_zenith_rad;
  // The cube frame's (x, y, z) is the march's (x, -z, y): +Y to the zenith.
  const glm::dvec3 sun(std::sin(theta_s), 0.0, std::cos(theta_s));
  double sq = 0.0, mean = 0.0;
  int count = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < spec.face; ++j)
      for (int i = 0; i < spec.face; ++i) {
        const glm::dvec3 d = gl_table_direction(f, i, j, spec.face);
        const glm::dvec3 want = sky_source_radiance(fx.atm, fx.source, false, 4 * spec.steps,
                                                    {0.0, 0.0, r}, {d.x, -d.z, d.y}, sun);
        for (int c = 0; c < 3; ++c) {
          const double got = ktx2.mips[0].at(i, j, 0, f, c);
          EXPECT_EQ(dds.mips[0].at(i, j, 0, f, c), got);
          sq += (got - want[c]) * (got - want[c]);
          mean += want[c];
          ++count;
        }
      }
  const double rms = std::sqrt(sq / count) / (mean / count);
  EXPECT_LT(rms, 0.01);
  RecordProperty("level0_rms", std::to_string(rms));
}

// The sky is symmetric about the sun's vertical plane (z = 0 in the cube
// frame): each texel equals its mirror, bit for bit, at level 0 and in the
// GGX levels the writer adds.
TEST(SkyEnvironment, CubeIsSymmetricAboutTheSunsPlane) {
  const EnvFixture& fx = env_fixture();
  const Texture level0 = bake_sky_environment(fx.atm, fx.source, small_spec(), {});
  const fs::path dir = write_environment(level0, "sky_environment_mirror");
  const Ktx2Image ktx2 = read_ktx2((dir / "env.ktx2").string());
  for (const Texture& level : ktx2.mips) {
    const int n = level.width;
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const CubeTexel m = cube_texel_mirrored_z(f, i, j, n);
          for (int c = 0; c < 3; ++c)
            EXPECT_EQ(level.at(i, j, 0, f, c), level.at(m.i, m.j, 0, m.face, c));
        }
  }
}

TEST(SkyEnvironment, ShAgreesWithTheIrradianceProjection) {
  const EnvFixture& fx = env_fixture();
  SkyEnvironmentSpec spec = small_spec();
  spec.face = 32;
  const Texture level0 = bake_sky_environment(fx.atm, fx.source, spec, {});
  const ShRadiance cube = cube_radiance_sh(level0, 0);
  const ShRadiance gauss = compute_sky_radiance_sh(fx.atm, fx.source, fx.irradiance_spec,
                                                   spec.views[0].altitude_m,
                                                   spec.views[0].sun_zenith_rad);
  for (int k = 0; k < kShL2Count; ++k) {
    const glm::dvec3 stored = meta_double3(level0.metadata, fmt::format("view.0.sh.{}", k));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(stored[c], cube[k][c], 1e-12 * cube[0][c]);
  }
  // E(n) of both over normals around the sphere, relative to the mean E.
  double sq = 0.0, mean = 0.0;
  const int count = 64;
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count, phi = 2.399963 * i;
    const double s = std::sqrt(1.0 - z * z);
    const glm::dvec3 n(s * std::cos(phi), s * std::sin(phi), z);
    const double a = sh_l2_irradiance(cube, n).y, b = sh_l2_irradiance(gauss, n).y;
    sq += (a - b) * (a - b);
    mean += b;
  }
  const double rms = std::sqrt(sq / count) / (mean / count);
  EXPECT_LT(rms, 0.01);  // 0.3% measured
  RecordProperty("sh_irradiance_rms", std::to_string(rms));
}

// three.js's KTX2Loader reads the cube's levels; its first texel of each
// face and level is the one skybake's reader finds.
TEST(SkyEnvironment, ThreeJsKtx2LoaderReadsTheCube) {
  const EnvFixture& fx = env_fixture();
  const Texture level0 = bake_sky_environment(fx.atm, fx.source, small_spec(), {});
  const fs::path dir = write_environment(level0, "sky_environment_three");
  const std::string script = test::source_path("tests/js/ktx2_three_cube.mjs").string();
  ASSERT_TRUE(fs::exists(test::source_path("tests/js/node_modules/three/package.json")))
      << "three is not installed in tests/js/node_modules (scripts/install-deps.sh runs npm ci)";
  int status = -1;
  const std::string out =
      test::run_shell("node '" + script + "' '" + (dir / "env.ktx2").string() + "' 2>&1", &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json three = nlohmann::json::parse(out);
  const Ktx2Image ours = read_ktx2((dir / "env.ktx2").string());
  EXPECT_EQ(three["type"], 1016);    // THREE.HalfFloatType
  EXPECT_EQ(three["format"], 1023);  // THREE.RGBAFormat
  ASSERT_EQ(three["levels"].size(), ours.mips.size());
  for (size_t m = 0; m < ours.mips.size(); ++m) {
    const nlohmann::json& level = three["levels"][m];
    EXPECT_EQ(level["width"], ours.mips[m].width);
    EXPECT_EQ(level["values"], 6 * ours.mips[m].width * ours.mips[m].width * 4);
    for (int f = 0; f < 6; ++f)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(level["faces"][f][c].get<double>(), ours.mips[m].at(0, 0, 0, f, c))
            << "level " << m << " face " << f;
  }
}

}  // namespace
}  // namespace skybake

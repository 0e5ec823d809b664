// A sky_environment cube map on llvmpipe: the DDS file of a real bake
// uploaded as it is into a GL_TEXTURE_CUBE_MAP (tests/gl/gl_texture.cpp),
// sampled through sky_environment_direction (runtime/glsl/sky_irradiance.glsl)
// from world directions in random frames (zenith, sun). Each query aims at a
// texel centre of level 0 in the cube's frame (+Y up, +X toward the sun's
// azimuth), so GL's own face selection and orientation must land on the
// texel skybake's reader finds there: a face stored in the wrong order, a
// flipped face or a wrong frame reads another texel (but for the mirror
// about the sun's vertical plane, where the sky is symmetric and reads the
// same values). A second case reads
// every level at its lod, as an engine reads a roughness.
#include <gtest/gtest.h>

#include <cmath>

#include "core/cube_map.hpp"
#include "core/math.hpp"
#include "gl/baked_atmosphere.hpp"
#include "gl/gl_context.hpp"
#include "io/dds.hpp"
#include "support/run.hpp"

namespace skybake::gltest {
namespace {

const BakedScene& environment_scene() {
  static const BakedScene scene = bake_scene("gl_sky_environment", R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_sky_environment",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + test::source_path("presets/atmospheres/earth.json").string() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"] },
    { "product": "sky_environment", "size": [16, 16], "formats": ["dds"],
      "radiance_source": "multiscattering_table", "steps": 8, "ggx_samples": 32,
      "views": [{ "altitude_km": 2, "sun_zenith_deg": 60 }] }
  ]
})");
  return scene;
}

// A unit vector from two uniform numbers.
glm::dvec3 unit_vector(double a, double b) {
  const double z = 2.0 * a - 1.0, phi = 2.0 * kPi * b, s = std::sqrt(std::max(1.0 - z * z, 0.0));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

double scrambled_unit(size_t i, int k) {
  uint32_t h = uint32_t(i) * 2654435761u ^ uint32_t(k) * 40503u;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  return double(h % 1000003u) / 1000003.0;
}

const char* kCubeShader = R"(
layout(local_size_x = 64) in;
layout(binding = 0) uniform samplerCube environment;
layout(std430, binding = 0) readonly buffer Queries { vec4 queries[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec3 d = queries[3u * i].xyz, up = queries[3u * i + 1u].xyz, sun = queries[3u * i + 2u].xyz;
  float lod = queries[3u * i].w;
  results[i] = textureLod(environment, sky_environment_direction(d, up, sun), lod);
}
)";

struct CubeQuery {
  int face, i, j, level;
};

// Runs the shader on queries aimed at texel centres; returns GL's values.
std::vector<float> sample_on_gl(const GlTexture& cube, const std::vector<CubeQuery>& q, int n) {
  std::vector<glm::vec4> data;
  for (size_t k = 0; k < q.size(); ++k) {
    const glm::dvec3 up = unit_vector(scrambled_unit(k, 1), scrambled_unit(k, 2));
    glm::dvec3 sun = unit_vector(scrambled_unit(k, 3), scrambled_unit(k, 4));
    // The cube's frame in the world: X toward the sun's azimuth, Y up, Z = X x Y.
    glm::dvec3 x = glm::normalize(sun - glm::dot(sun, up) * up);
    const glm::dvec3 z = glm::cross(x, up);
    const glm::dvec3 c = cube_texel_direction(q[k].face, q[k].i, q[k].j, n >> q[k].level);
    const glm::dvec3 d = c.x * x + c.y * up + c.z * z;
    data.push_back(glm::vec4(glm::vec3(d), float(q[k].level)));
    data.push_back(glm::vec4(glm::vec3(up), 0.0f));
    data.push_back(glm::vec4(glm::vec3(sun), 0.0f));
  }
  const ComputeProgram program = compile_compute({"sky_irradiance.glsl"}, kCubeShader);
  const StorageBuffer queries(data);
  const StorageBuffer results(q.size() * sizeof(glm::vec4));
  cube.bind(0);
  queries.bind(0);
  results.bind(1);
  dispatch(program, unsigned((q.size() + 63) / 64));
  return results.read_floats();
}

void expect_texels(const std::vector<float>& got, const std::vector<CubeQuery>& q,
                   const DdsImage& image) {
  for (size_t k = 0; k < q.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const float want = image.mips[size_t(q[k].level)].at(q[k].i, q[k].j, 0, q[k].face, c);
      EXPECT_NEAR(got[4 * k + size_t(c)], want, 2e-3f * std::abs(want) + 1e-7f)
          << "level " << q[k].level << " face " << q[k].face << " texel " << q[k].i << ", "
          << q[k].j << " channel " << c;
    }
}

TEST(SkyEnvironmentCube, GlReadsEveryTexelOfLevelZeroThroughTheFrame) {
  const BakedScene& s = environment_scene();
  const DdsImage image = read_dds(s.dds_path("sky_environment"));
  ASSERT_TRUE(image.cube);
  const int n = image.mips[0].width;
  std::vector<CubeQuery> q;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) q.push_back({f, i, j, 0});
  const GlTexture cube = upload_dds_cube(s.dds_path("sky_environment"));
  expect_texels(sample_on_gl(cube, q, n), q, image);
}

TEST(SkyEnvironmentCube, GlReadsEachPrefilteredLevelAtItsLod) {
  const BakedScene& s = environment_scene();
  const DdsImage image = read_dds(s.dds_path("sky_environment"));
  ASSERT_EQ(image.mips.size(), 2u);  // 16 and 8: down to 8 x 8 faces
  const int n = image.mips[0].width;
  std::vector<CubeQuery> q;
  for (int f = 0; f < 6; ++f)
    for (int t = 0; t < 8; ++t) q.push_back({f, (3 * t + f) % 8, (5 * t + 2 * f) % 8, 1});
  const GlTexture cube = upload_dds_cube(s.dds_path("sky_environment"));
  expect_texels(sample_on_gl(cube, q, n), q, image);
}

}  // namespace
}  // namespace skybake::gltest

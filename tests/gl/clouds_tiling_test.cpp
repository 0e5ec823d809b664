// The baked noise volumes (and the tileable 2D textures: weather, cirrus,
// curl) read the way an engine reads them: hardware trilinear (bilinear)
// filtering with GL_REPEAT, across the tile border.
//
// For each axis the volume is sampled at the faces between texels (u = i / n
// along the axis, texel centres across it), so that every sample blends two
// neighbours and sample 0 blends the last texel with the first: the border
// itself. Two checks:
//  1. the samples equal periodic trilinear interpolation of the texels on
//     the CPU, border included (the sampler wraps where the shader expects);
//     the same comparison with GL_CLAMP_TO_EDGE fails at the border;
//  2. the filtered values across the border are like those inside:
//     core/tiling.hpp's measure (the one of `check-tiling`) on the filtered
//     samples finds no seam on the shipped volumes, and finds one on a
//     volume made not to tile (the shape volume cropped along x).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/tiling.hpp"
#include "gl/gl_context.hpp"
#include "io/dds.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake::gltest {
namespace {

// The shipped noise set, baked once per process (DDS unorm8 with mips).
fs::path baked_noise() {
  static const fs::path dir = [] {
    const fs::path out = test::fresh_dir("gl_clouds_tiling");
    const auto r = test::run_skybake(
        {"bake", test::source_path("presets/clouds/horizon_zero_dawn.json").string(), "-o",
         out.string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out / "clouds_hzd";
  }();
  return dir;
}

// Sample positions: along `axis` the n faces u = i / n, across it the
// centres of every `stride`-th texel.
struct FaceGrid {
  int axis = 0;
  glm::ivec3 size{0};  // samples per axis
  glm::vec3 scale{0}, offset{0};
};

FaceGrid face_grid(const Texture& tex, int axis, int stride) {
  const glm::ivec3 n(tex.width, tex.height, tex.depth);
  FaceGrid g;
  g.axis = axis;
  for (int a = 0; a < 3; ++a) {
    const bool along = a == axis;
    g.size[a] = along ? n[a] : std::max(1, n[a] / stride);
    g.scale[a] = float(along ? 1.0 : double(stride)) / float(n[a]);
    g.offset[a] = along ? 0.0f : 0.5f / float(n[a]);
  }
  return g;
}

// The GPU's filtered samples on the grid, as a texture of the grid's shape;
// a texture of depth 1 is read as a sampler2D.
Texture sample_on_gpu(const GlTexture& texture, const FaceGrid& g, bool volume = true) {
  ComputeProgram program = compile_compute(
      {},
      std::string(volume ? "layout(binding = 0) uniform sampler3D tex;\n#define UVW(p) (p)\n"
                         : "layout(binding = 0) uniform sampler2D tex;\n#define UVW(p) (p).xy\n") +
          R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { vec4 samples[]; };
uniform int size_x, size_y, size_z;
uniform vec3 scale, offset;
void main() {
  int id = int(gl_GlobalInvocationID.x);
  if (id >= size_x * size_y * size_z) return;
  ivec3 o = ivec3(id % size_x, (id / size_x) % size_y, id / (size_x * size_y));
  samples[id] = textureLod(tex, UVW(vec3(o) * scale + offset), 0.0);
}
)");
  program.set("size_x", g.size.x);
  program.set("size_y", g.size.y);
  program.set("size_z", g.size.z);
  program.set("scale", g.scale);
  program.set("offset", g.offset);
  const size_t count = size_t(g.size.x) * g.size.y * g.size.z;
  StorageBuffer out(count * 4 * sizeof(float));
  out.bind(0);
  texture.bind(0);
  dispatch(program, unsigned((count + 63) / 64));
  Texture samples(g.size.x, g.size.y, g.size.z, 1, {"R", "G", "B", "A"});
  const std::vector<float> floats = out.read_floats();
  samples.data.assign(floats.begin(), floats.end());
  return samples;
}

// Periodic trilinear interpolation of the texels at uvw (texel centres at
// (i + 0.5) / n, indices wrapped), channel c; 3-channel volumes read A = 1
// as GL does.
double periodic_trilinear(const Texture& tex, glm::dvec3 uvw, int c) {
  if (c >= tex.channel_count()) return 1.0;
  const glm::ivec3 n(tex.width, tex.height, tex.depth);
  int i0[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double x = uvw[a] * n[a] - 0.5;
    const double fl = std::floor(x);
    i0[a] = int(fl);
    f[a] = x - fl;
  }
  auto wrap = [](int i, int m) { return ((i % m) + m) % m; };
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double w = 1.0;
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      const int bit = (corner >> a) & 1;
      w *= bit ? f[a] : 1.0 - f[a];
      idx[a] = wrap(i0[a] + bit, n[a]);
    }
    if (w != 0.0) sum += w * tex.at(idx[0], idx[1], idx[2], 0, c);
  }
  return sum;
}

struct Agreement {
  double max_border = 0.0;  // largest |GPU - CPU| over samples at u = 0 along the axis
  double max_inside = 0.0;  // ... over the other samples
};

Agreement compare_with_cpu(const Texture& texels, const Texture& samples, const FaceGrid& g) {
  Agreement a;
  for (int z = 0; z < g.size.z; ++z)
    for (int y = 0; y < g.size.y; ++y)
      for (int x = 0; x < g.size.x; ++x) {
        const glm::ivec3 o(x, y, z);
        const glm::dvec3 uvw = glm::dvec3(o) * glm::dvec3(g.scale) + glm::dvec3(g.offset);
        for (int c = 0; c < 4; ++c) {
          const double d = std::abs(samples.at(x, y, z, 0, c) - periodic_trilinear(texels, uvw, c));
          double& m = o[g.axis] == 0 ? a.max_border : a.max_inside;
          m = std::max(m, d);
        }
      }
  return a;
}

// The tiling verdicts of the sampled texture along the grid's axis, level 0.
std::vector<AxisTiling> verdicts_along(const Texture& samples, int axis) {
  std::vector<AxisTiling> out;
  for (const AxisTiling& t : measure_tiling(samples, 0.25).axes)
    if (t.level == 0 && t.axis == "xyz"[axis]) out.push_back(t);
  return out;
}

std::string describe(const std::vector<AxisTiling>& v) {
  std::string s;
  for (const AxisTiling& t : v)
    s += std::string(" ") + t.channel + ":" + tiling_verdict_name(t.verdict) + "(" +
         std::to_string(t.ratio) + ")";
  return s;
}

// Unorm8 texels filtered by llvmpipe: the blend of two codes is returned
// within half a code of the exact mean (its 8-bit filtering path rounds the
// result to a code); float texels within float rounding of the sample
// coordinates, which moves each weight by about n x 6e-8.
constexpr double kUnorm8Bar = 0.5 / 255.0 + 1e-6;
constexpr double kFloatBar = 1e-5;

// Reads `file` (a DDS of ours) with repeat along every axis and checks both
// properties along each axis; `stride` thins the lines across the axis.
void expect_tiles_through_the_filter(const std::string& file, int stride) {
  GlContext::shared();
  const DdsImage dds = read_dds(file);
  const Texture& texels = dds.mips.at(0);
  const bool volume = texels.depth > 1;
  SamplerState repeat{Filter::linear, Wrap::repeat, Wrap::repeat, Wrap::repeat};
  const GlTexture texture = upload_dds(file, repeat);
  for (int axis = 0; axis < (volume ? 3 : 2); ++axis) {
    const FaceGrid g = face_grid(texels, axis, stride);
    const Texture samples = sample_on_gpu(texture, g, volume);
    const Agreement a = compare_with_cpu(texels, samples, g);
    EXPECT_LE(a.max_border, kUnorm8Bar) << file << " axis " << axis;
    EXPECT_LE(a.max_inside, kUnorm8Bar) << file << " axis " << axis;
    const auto v = verdicts_along(samples, axis);
    ASSERT_FALSE(v.empty());
    bool judged = false;
    for (const AxisTiling& t : v) {
      EXPECT_TRUE(t.tiles) << file << " axis " << axis << describe(v);
      judged |= t.verdict == TilingVerdict::tiles && t.reason.empty();
    }
    EXPECT_TRUE(judged) << "some channel must be judged:" << describe(v);
  }
}

TEST(CloudsTiling, ShapeVolumeFiltersAcrossTheBorderWithoutSeam) {
  expect_tiles_through_the_filter((baked_noise() / "noise_shape.dds").string(), 4);
}

TEST(CloudsTiling, DetailVolumeFiltersAcrossTheBorderWithoutSeam) {
  expect_tiles_through_the_filter((baked_noise() / "noise_detail.dds").string(), 1);
}

// The tileable 2D products: weather and cirrus of the storm preset, curl.
TEST(CloudsTiling, WeatherCirrusAndCurlFilterAcrossTheBorderWithoutSeam) {
  const fs::path out = test::fresh_dir("gl_clouds_tiling_2d");
  const auto r = test::run_skybake({"bake", test::source_path("presets/earth_storm.json").string(),
                                    "-o", out.string(), "-q", "--only", "weather,cirrus"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_tiles_through_the_filter((out / "earth_storm" / "weather.dds").string(), 1);
  expect_tiles_through_the_filter((out / "earth_storm" / "cirrus.dds").string(), 1);
  expect_tiles_through_the_filter((baked_noise() / "curl.dds").string(), 1);
}

TEST(CloudsTiling, ClampToEdgeDisagreesWithPeriodicInterpolationAtTheBorder) {
  GlContext::shared();
  const std::string file = (baked_noise() / "noise_shape.dds").string();
  const Texture texels = read_dds(file).mips.at(0);
  SamplerState clamp{Filter::linear, Wrap::clamp_to_edge, Wrap::clamp_to_edge, Wrap::clamp_to_edge};
  const GlTexture volume = upload_dds(file, clamp);
  const FaceGrid g = face_grid(texels, 0, 4);
  const Agreement a = compare_with_cpu(texels, sample_on_gpu(volume, g), g);
  EXPECT_LE(a.max_inside, kUnorm8Bar);
  EXPECT_GT(a.max_border, 10 * kUnorm8Bar) << "clamping is not wrapping: the check must see it";
}

TEST(CloudsTiling, CroppedVolumeShowsItsSeamThroughTheFilter) {
  GlContext::shared();
  const Texture full = read_dds((baked_noise() / "noise_shape.dds").string()).mips.at(0);
  // Texels 0 .. 111 of every row: the border now joins texel 111 to texel 0,
  // 16 texels (a whole cell of the first octave) apart.
  const int n = full.width - 16;
  Texture cropped(n, full.height, full.depth, 1, full.channels);
  for (int z = 0; z < full.depth; ++z)
    for (int y = 0; y < full.height; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < full.channel_count(); ++c)
          cropped.at(x, y, z, 0, c) = full.at(x, y, z, 0, c);
  SamplerState repeat{Filter::linear, Wrap::repeat, Wrap::repeat, Wrap::repeat};
  const GlTexture volume = upload_texture(cropped, repeat);
  for (int axis = 0; axis < 3; ++axis) {
    const FaceGrid g = face_grid(cropped, axis, 4);
    const Texture samples = sample_on_gpu(volume, g);
    const Agreement a = compare_with_cpu(cropped, samples, g);
    EXPECT_LE(std::max(a.max_border, a.max_inside), kFloatBar) << "axis " << axis;
    const auto v = verdicts_along(samples, axis);
    bool seam = false;
    for (const AxisTiling& t : v) seam |= t.verdict == TilingVerdict::seam;
    // Only x was cut; y and z still tile.
    EXPECT_EQ(seam, axis == 0) << "axis " << axis << describe(v);
  }
}

}  // namespace
}  // namespace skybake::gltest

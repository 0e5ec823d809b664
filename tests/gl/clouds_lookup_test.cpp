// The texture reads of runtime/glsl/clouds_weather.glsl and
// clouds_noise.glsl on a real GL context against the C++ side:
//  - lookup_cloud_type (hardware bilinear, clamp) against the CPU's bilinear
//    read (core/texture_sampling.hpp) of the same baked texels, and
//    lookup_height_gradient against the cloud-type density it must equal;
//  - the two weather layouts of one map decode to the same type index;
//  - curl's signed decode of the baked texels against the curl the bake
//    evaluated (noise/curl.hpp), from float texels and from the unorm8 DDS
//    with the scales the manifest records;
//  - lookup_base_cloud and lookup_detail_fbm against pack_single_channel.
// Bars as in clouds_decode_test.cpp: 1e-5 x max(1, |C++|) for float data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "clouds/cloud_types.hpp"
#include "clouds/height_gradients.hpp"
#include "clouds/weather_map.hpp"
#include "core/texture_sampling.hpp"
#include "gl/gl_context.hpp"
#include "io/dds.hpp"
#include "noise/curl.hpp"
#include "noise/curl_texture.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/noise_volume.hpp"
#include "noise/volume_rows.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake::gltest {
namespace {

constexpr int kPoints = 4096;

double bar(double expected) {
  return 1e-5 * std::max(1.0, std::abs(expected));
}

std::vector<float> uniform_points(size_t count, float lo, float hi, uint32_t seed) {
  std::vector<float> out(count);
  uint32_t s = seed;
  for (float& v : out) {
    s = s * 1664525u + 1013904223u;
    v = lo + (hi - lo) * float(s >> 8) / 16777216.0f;
  }
  return out;
}

// Runs `body` with the cloud includes over `count` invocations (64 a group)
// with `in` at binding 0 and `out_floats` floats at binding 1; `textures`
// bound to units 0, 1, ...
std::vector<float> run(const std::string& body, const std::vector<float>& in, size_t count,
                       size_t out_floats, const std::vector<const GlTexture*>& textures) {
  GlContext::shared();
  ComputeProgram program = compile_compute({"clouds_noise.glsl", "clouds_weather.glsl"}, R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float in_[]; };
layout(std430, binding = 1) buffer Out { float out_[]; };
)" + body);
  StorageBuffer input(in.empty() ? std::vector<float>{0.0f} : in);
  StorageBuffer output(out_floats * sizeof(float));
  input.bind(0);
  output.bind(1);
  for (size_t i = 0; i < textures.size(); ++i) textures[i]->bind(unsigned(i));
  dispatch(program, unsigned((count + 63) / 64));
  return output.read_floats();
}

std::vector<CloudTypeProfile> five_types() {
  std::vector<CloudTypeProfile> types = default_cloud_types();
  types.push_back({"anvil", {0.01, 0.05, 0.82, 1.0}, 0.8, 0.2});
  return types;
}

TEST(CloudsLookup, CloudTypeLookupMatchesCpuBilinear) {
  CloudTypesSpec spec;
  spec.height = 64;
  spec.types = five_types();
  const Texture types = bake_cloud_types(spec);
  const GlTexture tex = upload_texture(types, {Filter::linear});
  const auto index = uniform_points(kPoints, -0.2f, 4.2f, 11);
  const auto h = uniform_points(kPoints, -0.05f, 1.05f, 12);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) in.insert(in.end(), {index[i], h[i]});
  const auto out = run(R"(
layout(binding = 0) uniform sampler2D cloud_types;
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec2 v = lookup_cloud_type(cloud_types, in_[2 * i], 5, in_[2 * i + 1]);
  out_[2 * i] = v.x;
  out_[2 * i + 1] = v.y;
}
)",
                       in, kPoints, 2 * kPoints, {&tex});
  for (int i = 0; i < kPoints; ++i) {
    const glm::dvec4 cpu =
        sample_bilinear(types, type_u_from_index(index[i], 5), h[i], 0, 0, false);
    ASSERT_NEAR(out[2 * i], cpu.x, bar(cpu.x)) << "density at " << index[i] << ", " << h[i];
    ASSERT_NEAR(out[2 * i + 1], cpu.y, bar(cpu.y)) << "erosion at " << index[i] << ", " << h[i];
  }
  // At a column centre and a row centre the lookup is the closed form.
  for (int k = 0; k < 5; ++k) {
    const int j = 17;
    const double hh = height_from_row(j, 64);
    EXPECT_NEAR(types.at(k, j, 0, 0, 0), compute_height_density(spec.types[k].density, hh), 1e-7);
  }
}

TEST(CloudsLookup, HeightGradientLookupEqualsCloudTypeDensity) {
  CloudTypesSpec types_spec;
  types_spec.height = 64;  // the four standard types
  const Texture types = bake_cloud_types(types_spec);
  HeightGradientsSpec spec;
  spec.height = 64;
  const Texture gradients = bake_height_gradients(spec);
  const GlTexture gtex = upload_texture(gradients, {Filter::linear});
  const auto index = uniform_points(kPoints, 0.0f, 3.0f, 13);
  const auto h = uniform_points(kPoints, 0.0f, 1.0f, 14);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) in.insert(in.end(), {index[i], h[i]});
  const auto out = run(R"(
layout(binding = 0) uniform sampler2D height_gradients;
void main() {
  uint i = gl_GlobalInvocationID.x;
  out_[i] = lookup_height_gradient(height_gradients, in_[2 * i], in_[2 * i + 1]);
}
)",
                       in, kPoints, kPoints, {&gtex});
  for (int i = 0; i < kPoints; ++i) {
    const double cpu = sample_bilinear(types, type_u_from_index(index[i], 4), h[i], 0, 0, false).x;
    ASSERT_NEAR(out[i], cpu, bar(cpu)) << index[i] << ", " << h[i];
  }
}

TEST(CloudsLookup, BothWeatherLayoutsDecodeToTheSameTypeIndex) {
  WeatherSpec spec;
  spec.size = 128;
  spec.seed = 3;
  spec.type_count = 5;
  spec.coverage.mean = 0.6;
  spec.precipitation.area = 0.12;
  spec.precipitation.edge = 0.08;
  spec.layout = WeatherLayout::schneider;
  const Texture schneider = bake_weather_map(spec, BakeContext{});
  spec.layout = WeatherLayout::frostbite;
  const Texture frostbite = bake_weather_map(spec, BakeContext{});
  const GlTexture s_tex = upload_texture(schneider, {Filter::nearest});
  const GlTexture f_tex = upload_texture(frostbite, {Filter::nearest});
  const int n = spec.size;
  const auto out = run(R"(
layout(binding = 0) uniform sampler2D schneider;
layout(binding = 1) uniform sampler2D frostbite;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  ivec2 xy = ivec2(i % 128, i / 128);
  out_[2 * i] = weather_type_index(texelFetch(schneider, xy, 0), SKYBAKE_WEATHER_SCHNEIDER, 5);
  out_[2 * i + 1] = weather_type_index(texelFetch(frostbite, xy, 0), SKYBAKE_WEATHER_FROSTBITE, 5);
}
)",
                       {}, size_t(n) * n, 2 * size_t(n) * n, {&s_tex, &f_tex});
  size_t raining = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int i = y * n + x;
      const double expected = index_from_type_u(frostbite.at(x, y, 0, 0, 1), 5);
      ASSERT_NEAR(out[2 * i + 1], expected, bar(expected)) << x << ", " << y;
      ASSERT_NEAR(out[2 * i], expected, bar(expected)) << x << ", " << y;
      if (schneider.at(x, y, 0, 0, 1) == 1.0f) {
        ++raining;
        ASSERT_EQ(out[2 * i], 3.0f) << "a raining Schneider texel is a cumulonimbus";
      }
    }
  EXPECT_GT(raining, size_t(0.1 * n * n)) << "12% of the map rains";
}

// The curl the bake evaluated at texel (x, y): curl2 for R, G, the z of the
// 3D curl on the plane slice_z for B (noise/curl_texture.hpp).
glm::vec3 curl_at_texel(const CurlSpec& s, int x, int y) {
  const float px = cell_coord_from_texel(x, s.size, s.period);
  const float py = cell_coord_from_texel(y, s.size, s.period);
  const glm::vec2 v = curl2({px, py}, glm::ivec2(s.period), s.octaves, s.seed, s.gain);
  const glm::vec3 v3 = curl3({px, py, s.slice_z}, glm::ivec3(s.period), s.octaves,
                             stream_seed(s.seed, 0x33643344), s.gain);
  return {v.x, v.y, v3.z};
}

// The scales go in through the input buffer, as exact floats.
std::vector<float> decode_curl_on_gpu(const GlTexture& tex, int n, float scale_rg, float scale_b) {
  return run(R"(
layout(binding = 0) uniform sampler2D curl;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  int n = textureSize(curl, 0).x;
  vec2 uv = (vec2(i % n, i / n) + 0.5) / float(n);
  vec3 v = lookup_curl(curl, uv, 0.0, in_[0], in_[1]);
  out_[3 * i] = v.x;
  out_[3 * i + 1] = v.y;
  out_[3 * i + 2] = v.z;
}
)",
             {scale_rg, scale_b}, size_t(n) * n, 3 * size_t(n) * n, {&tex});
}

TEST(CloudsLookup, CurlDecodeOfFloatTexelsIsTheBakedCurl) {
  CurlSpec spec;
  spec.size = 64;
  spec.seed = 9;
  const Texture curl = bake_curl(spec, BakeContext{});
  // The scales are the largest |component| of the baked field (what the
  // metadata records), found here from the curl itself.
  float scale_rg = 0.0f, scale_b = 0.0f;
  for (int y = 0; y < spec.size; ++y)
    for (int x = 0; x < spec.size; ++x) {
      const glm::vec3 v = curl_at_texel(spec, x, y);
      scale_rg = std::max({scale_rg, std::abs(v.x), std::abs(v.y)});
      scale_b = std::max(scale_b, std::abs(v.z));
    }
  const GlTexture tex =
      upload_texture(curl, {Filter::linear, Wrap::repeat, Wrap::repeat, Wrap::repeat});
  const auto out = decode_curl_on_gpu(tex, spec.size, scale_rg, scale_b);
  // The encode rounds c to float (half an ulp of a value <= 1), which the
  // decode multiplies by 2 scale: the bar scales with the scale, not with v.
  for (int y = 0; y < spec.size; ++y)
    for (int x = 0; x < spec.size; ++x) {
      const glm::vec3 v = curl_at_texel(spec, x, y);
      const int i = y * spec.size + x;
      ASSERT_NEAR(out[3 * i], v.x, bar(scale_rg)) << x << ", " << y;
      ASSERT_NEAR(out[3 * i + 1], v.y, bar(scale_rg)) << x << ", " << y;
      ASSERT_NEAR(out[3 * i + 2], v.z, bar(scale_b)) << x << ", " << y;
    }
}

TEST(CloudsLookup, CurlDecodeOfTheUnorm8FileIsTheCurlWithinItsQuantisation) {
  const fs::path out = test::fresh_dir("gl_curl_unorm8");
  const auto r = test::run_skybake(
      {"bake", test::source_path("presets/clouds/horizon_zero_dawn.json").string(), "-o",
       out.string(), "-q", "--only", "curl"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path dir = out / "clouds_hzd";
  const auto manifest = nlohmann::json::parse(test::read_file(dir / "manifest.json"));
  nlohmann::json meta;
  for (const auto& o : manifest["outputs"])
    if (o["product"] == "curl") meta = o["metadata"];
  auto number = [&](const char* key) {
    const auto& v = meta.at(key);
    return v.is_string() ? std::stod(v.get<std::string>()) : v.get<double>();
  };
  CurlSpec spec;  // the preset's curl: 128^2, period 4, 3 octaves, seed 0
  spec.size = 128;
  spec.period = int(number("period"));
  spec.octaves = int(number("octaves"));
  spec.seed = uint32_t(number("seed"));
  const float scale_rg = float(number("curl_scale_rg")), scale_b = float(number("curl_scale_b"));
  const GlTexture tex = upload_dds((dir / "curl.dds").string(),
                                   {Filter::linear, Wrap::repeat, Wrap::repeat, Wrap::repeat});
  const auto v_gpu = decode_curl_on_gpu(tex, spec.size, scale_rg, scale_b);
  // Half a code of c is 0.5 / 255, i.e. scale / 255 of v; 1% more for float
  // rounding (the scale is the manifest's, read back exactly).
  const double bar_rg = 1.01 * scale_rg / 255.0, bar_b = 1.01 * scale_b / 255.0;
  double worst_rg = 0.0;
  for (int y = 0; y < spec.size; ++y)
    for (int x = 0; x < spec.size; ++x) {
      const glm::vec3 v = curl_at_texel(spec, x, y);
      const int i = y * spec.size + x;
      ASSERT_NEAR(v_gpu[3 * i], v.x, bar_rg) << x << ", " << y;
      ASSERT_NEAR(v_gpu[3 * i + 1], v.y, bar_rg) << x << ", " << y;
      ASSERT_NEAR(v_gpu[3 * i + 2], v.z, bar_b) << x << ", " << y;
      worst_rg = std::max(worst_rg, double(std::abs(v_gpu[3 * i] - v.x)));
    }
  // The bar is not loose: the quantisation really reaches most of it.
  EXPECT_GT(worst_rg, 0.5 * scale_rg / 255.0);
}

}  // namespace
}  // namespace skybake::gltest

namespace skybake::gltest {
namespace {

// lookup_base_cloud and lookup_detail_fbm on the shipped unorm8 volumes,
// read at texel centres (the filter returns the texel), against
// pack_single_channel of the same texels as our DDS reader decodes them.
TEST(CloudsLookup, BaseCloudAndDetailFbmArePackSingleChannelOfTheTexels) {
  const fs::path out = test::fresh_dir("gl_noise_pack");
  const auto r = test::run_skybake(
      {"bake", test::source_path("presets/clouds/horizon_zero_dawn.json").string(), "-o",
       out.string(), "-q", "--only", "noise_shape,noise_detail"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const SamplerState repeat{Filter::linear, Wrap::repeat, Wrap::repeat, Wrap::repeat};
  for (const std::string name : {"noise_shape", "noise_detail"}) {
    const std::string file = (out / "clouds_hzd" / (name + ".dds")).string();
    Texture texels = read_dds(file).mips.at(0);
    if (name == "noise_detail") {  // R8G8B8A8 holds R G B and an unused A
      Texture rgb(texels.width, texels.height, texels.depth, 1, {"R", "G", "B"});
      for (size_t t = 0; t < texels.texel_count(); ++t)
        for (int c = 0; c < 3; ++c) rgb.data[t * 3 + c] = texels.data[t * 4 + c];
      texels = rgb;
    }
    const Texture packed = pack_single_channel(
        texels, name == "noise_shape" ? shape_pack_weights() : detail_pack_weights());
    const GlTexture tex = upload_dds(file, repeat);
    const size_t count = texels.texel_count();
    const auto v = run(std::string("layout(binding = 0) uniform sampler3D volume;\n") + R"(
void main() {
  int i = int(gl_GlobalInvocationID.x);
  ivec3 n = textureSize(volume, 0);
  if (i >= n.x * n.y * n.z) return;
  vec3 uvw = (vec3(i % n.x, (i / n.x) % n.y, i / (n.x * n.y)) + 0.5) / vec3(n);
  out_[i] = )" + (name == "noise_shape" ? "lookup_base_cloud" : "lookup_detail_fbm") +
                           "(volume, uvw, 0.0);\n}\n",
                       {}, count, count, {&tex});
    for (size_t t = 0; t < count; ++t)
      ASSERT_NEAR(v[t], packed.data[t], bar(packed.data[t])) << name << " texel " << t;
  }
}

}  // namespace
}  // namespace skybake::gltest

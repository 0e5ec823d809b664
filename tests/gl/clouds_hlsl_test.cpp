// The HLSL cloud includes (runtime/hlsl/clouds_noise.hlsl,
// clouds_weather.hlsl) run, not only compiled: compile_compute_hlsl
// (gl_context.hpp) makes SPIR-V with glslang's HLSL front end and llvmpipe
// runs it through GL_ARB_gl_spirv. The functions are compared
// with the same C++ and bars as the GLSL tests (clouds_decode_test.cpp,
// clouds_lookup_test.cpp), so the two languages cannot drift apart.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "clouds/cloud_types.hpp"
#include "clouds/height_gradients.hpp"
#include "clouds/weather_map.hpp"
#include "core/texture_sampling.hpp"
#include "gl/gl_context.hpp"
#include "noise/curl_texture.hpp"
#include "noise/noise_volume.hpp"
#include "noise/perlin_worley.hpp"

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

std::vector<float> run_hlsl(const std::string& body, const std::vector<float>& in, size_t count,
                            size_t out_floats, const std::vector<const GlTexture*>& textures = {}) {
  GlContext::shared();
  const ComputeProgram program = compile_compute_hlsl({"clouds_noise.hlsl", "clouds_weather.hlsl"},
                                                      R"(
StructuredBuffer<float> in_ : register(t8);
RWStructuredBuffer<float> out_ : register(u9);
)" + body);
  StorageBuffer input(in);
  StorageBuffer output(out_floats * sizeof(float));
  input.bind(8);
  output.bind(9);
  for (size_t i = 0; i < textures.size(); ++i) textures[i]->bind(unsigned(i));
  dispatch(program, unsigned((count + 63) / 64));
  return output.read_floats();
}

TEST(CloudsHlsl, NoiseAndCurlFunctionsMatchCpp) {
  const auto p = uniform_points(kPoints, -1.2f, 1.2f, 1);
  const auto w = uniform_points(kPoints, -0.1f, 1.1f, 2);
  const auto t = uniform_points(size_t(kPoints) * 4, 0.0f, 1.0f, 3);
  const auto s = uniform_points(kPoints, 0.5f, 20.0f, 6);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) {
    in.insert(in.end(), {p[i], w[i], s[i]});
    in.insert(in.end(), t.begin() + 4 * i, t.begin() + 4 * i + 4);
  }
  const auto out = run_hlsl(R"(
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  float p = in_[7 * i], w = in_[7 * i + 1], s = in_[7 * i + 2];
  float4 texel = float4(in_[7 * i + 3], in_[7 * i + 4], in_[7 * i + 5], in_[7 * i + 6]);
  out_[7 * i + 0] = perlin_worley(p, w, SKYBAKE_REMAP_WORLEY_NEW_MIN);
  out_[7 * i + 1] = perlin_worley(p, w, SKYBAKE_REMAP_WORLEY_OLD_MIN);
  out_[7 * i + 2] = perlin_worley(p, w, SKYBAKE_REMAP_DILATE);
  out_[7 * i + 3] = pack_single_channel(texel, SKYBAKE_PACK_DILATE_BASE, shape_pack_weights());
  out_[7 * i + 4] = pack_single_channel(float4(texel.rgb, 0.0), SKYBAKE_PACK_WEIGHTED_SUM,
                                        detail_pack_weights());
  out_[7 * i + 5] = curl_value_from_texel(texel.x, s);
  out_[7 * i + 6] = curl_texel_from_value(10.0 * p, s);
}
)",
                            in, kPoints, 7 * kPoints);
  Texture shape(kPoints, 1, 1, 1, {"R", "G", "B", "A"});
  Texture detail(kPoints, 1, 1, 1, {"R", "G", "B"});
  for (int i = 0; i < kPoints; ++i)
    for (int c = 0; c < 4; ++c) {
      shape.at(i, 0, 0, 0, c) = t[4 * i + c];
      if (c < 3) detail.at(i, 0, 0, 0, c) = t[4 * i + c];
    }
  const Texture shape_packed = pack_single_channel(shape, shape_pack_weights());
  const Texture detail_packed = pack_single_channel(detail, detail_pack_weights());
  for (int i = 0; i < kPoints; ++i) {
    const double expected[7] = {perlin_worley(p[i], w[i], PerlinWorleyRemap::worley_new_min),
                                perlin_worley(p[i], w[i], PerlinWorleyRemap::worley_old_min),
                                perlin_worley(p[i], w[i], PerlinWorleyRemap::dilate),
                                shape_packed.data[i],
                                detail_packed.data[i],
                                curl_value_from_texel(t[4 * i], s[i]),
                                curl_texel_from_value(10.0f * p[i], s[i])};
    for (int j = 0; j < 7; ++j)
      ASSERT_NEAR(out[7 * i + j], expected[j], bar(expected[j])) << "point " << i << " value " << j;
  }
}

TEST(CloudsHlsl, WeatherAndHeightFunctionsMatchCpp) {
  const auto cov = uniform_points(kPoints, 0.0f, 1.0f, 7);
  const auto rain = uniform_points(kPoints, 0.0f, 1.0f, 8);
  const auto type = uniform_points(kPoints, 0.0f, 1.0f, 9);
  const auto h = uniform_points(kPoints, -0.1f, 1.1f, 10);
  const HeightRamp ramp = default_cloud_types()[2].density;  // cumulus
  const CloudTypeProfile cumulus = default_cloud_types()[2];
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i)
    in.insert(in.end(), {cov[i], i % 4 ? rain[i] : 1.0f, type[i], h[i]});
  const auto out = run_hlsl(
      "static const float4 kRamp = float4(" + std::to_string(ramp.a) + ", " +
          std::to_string(ramp.b) + ", " + std::to_string(ramp.c) + ", " + std::to_string(ramp.d) +
          ");\nstatic const float2 kErosion = float2(" + std::to_string(cumulus.erosion_base) +
          ", " + std::to_string(cumulus.erosion_top) + ");\n" + R"(
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  float c = in_[4 * i], p = in_[4 * i + 1], t = in_[4 * i + 2], h = in_[4 * i + 3];
  out_[6 * i + 0] = coverage_with_rain(c, p);
  out_[6 * i + 1] = type_with_rain(t, p);
  out_[6 * i + 2] = frostbite_type_index(t, p);
  out_[6 * i + 3] = type_index_from_schneider(type_with_rain(t, p), p);
  out_[6 * i + 4] = compute_height_density(kRamp, h);
  out_[6 * i + 5] = compute_height_erosion(kRamp, kErosion, h);
}
)",
      in, kPoints, 6 * kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const float c = in[4 * i], p = in[4 * i + 1], t = in[4 * i + 2], hh = in[4 * i + 3];
    const double expected[6] = {
        coverage_with_rain(c, p),         type_with_rain(t, p),
        frostbite_type_index(t, p),       frostbite_type_index(t, p),
        compute_height_density(ramp, hh), compute_height_erosion(cumulus, hh)};
    for (int j = 0; j < 6; ++j)
      ASSERT_NEAR(out[6 * i + j], expected[j], bar(expected[j])) << "point " << i << " value " << j;
  }
}

TEST(CloudsHlsl, CloudTypeAndHeightGradientLookupsMatchCpuBilinear) {
  CloudTypesSpec types_spec;
  types_spec.height = 64;
  const Texture types = bake_cloud_types(types_spec);
  HeightGradientsSpec gradients_spec;
  gradients_spec.height = 64;
  const Texture gradients = bake_height_gradients(gradients_spec);
  const GlTexture types_tex = upload_texture(types, {Filter::linear});
  const GlTexture gradients_tex = upload_texture(gradients, {Filter::linear});
  const auto index = uniform_points(kPoints, 0.0f, 3.0f, 13);
  const auto h = uniform_points(kPoints, -0.05f, 1.05f, 14);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) in.insert(in.end(), {index[i], h[i]});
  const auto out = run_hlsl(R"(
Texture2D<float4> cloud_types : register(t0);
Texture2D<float4> height_gradients : register(t1);
SamplerState clamp_linear : register(s0);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x;
  float2 v = lookup_cloud_type(cloud_types, clamp_linear, in_[2 * i], 4, in_[2 * i + 1]);
  out_[3 * i] = v.x;
  out_[3 * i + 1] = v.y;
  out_[3 * i + 2] =
      lookup_height_gradient(height_gradients, clamp_linear, in_[2 * i], in_[2 * i + 1]);
}
)",
                            in, kPoints, 3 * kPoints, {&types_tex, &gradients_tex});
  for (int i = 0; i < kPoints; ++i) {
    const glm::dvec4 cpu =
        sample_bilinear(types, type_u_from_index(index[i], 4), h[i], 0, 0, false);
    ASSERT_NEAR(out[3 * i], cpu.x, bar(cpu.x)) << index[i] << ", " << h[i];
    ASSERT_NEAR(out[3 * i + 1], cpu.y, bar(cpu.y)) << index[i] << ", " << h[i];
    ASSERT_NEAR(out[3 * i + 2], cpu.x, bar(cpu.x)) << index[i] << ", " << h[i];
  }
}

}  // namespace
}  // namespace skybake::gltest

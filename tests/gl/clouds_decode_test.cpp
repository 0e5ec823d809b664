// The cloud decode of runtime/glsl/clouds_noise.glsl and clouds_weather.glsl
// run on a real GL context (gl_context.hpp) against the C++ they mirror:
// the pure functions at 4096 points each, the cloud-type and height-gradient
// lookups through hardware bilinear filtering against the CPU's bilinear read
// of the same texels and against the closed form, the two weather layouts of
// one map decoding to the same type index, and curl's signed decode against
// the curl the texture was baked from.
//
// Bars: 1e-5 x max(1, |C++|). Every value here lies in [0, 3] or is a curl
// of order 10, where float32 rounding of a handful of operations stays below
// 1e-6; the floor at 1 keeps values near 0 (a smoothstep just above its
// edge) from asking for relative precision float32 does not have. Unorm8
// data gets the bar its quantisation justifies, said where it is used.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "clouds/cloud_types.hpp"
#include "clouds/height_gradients.hpp"
#include "clouds/weather_map.hpp"
#include "core/texture_sampling.hpp"
#include "gl/gl_context.hpp"
#include "io/dds.hpp"
#include "noise/curl.hpp"
#include "noise/curl_texture.hpp"
#include "noise/fbm.hpp"
#include "noise/noise_volume.hpp"
#include "noise/perlin_worley.hpp"
#include "noise/volume_rows.hpp"

namespace skybake::gltest {
namespace {

constexpr int kPoints = 4096;

// Deterministic inputs in [lo, hi) (a 32-bit LCG: the test needs spread, not
// quality).
std::vector<float> uniform_points(size_t count, float lo, float hi, uint32_t seed) {
  std::vector<float> out(count);
  uint32_t s = seed;
  for (float& v : out) {
    s = s * 1664525u + 1013904223u;
    v = lo + (hi - lo) * float(s >> 8) / 16777216.0f;
  }
  return out;
}

double bar(double expected) {
  return 1e-5 * std::max(1.0, std::abs(expected));
}

// Runs `body` (which reads `in[]` and writes `out[]`, kPoints invocations)
// with the cloud includes and returns out.
std::vector<float> run_points(const std::string& body, const std::vector<float>& in,
                              size_t out_per_point) {
  GlContext::shared();
  ComputeProgram program = compile_compute({"clouds_noise.glsl", "clouds_weather.glsl"}, R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float in_[]; };
layout(std430, binding = 1) buffer Out { float out_[]; };
)" + body);
  StorageBuffer input(in);
  StorageBuffer output(kPoints * out_per_point * sizeof(float));
  input.bind(0);
  output.bind(1);
  dispatch(program, kPoints / 64);
  return output.read_floats();
}

TEST(CloudsDecode, NoiseFunctionsMatchCpp) {
  // Per point: perlin fBm in [-1.2, 1.2], Worley fBm in [-0.1, 1.1] (the
  // clamps are part of the function), four texel channels.
  const auto p = uniform_points(kPoints, -1.2f, 1.2f, 1);
  const auto w = uniform_points(kPoints, -0.1f, 1.1f, 2);
  const auto t = uniform_points(size_t(kPoints) * 4, 0.0f, 1.0f, 3);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) {
    in.insert(in.end(), {p[i], w[i]});
    in.insert(in.end(), t.begin() + 4 * i, t.begin() + 4 * i + 4);
  }
  const auto out = run_points(R"(
void main() {
  uint i = gl_GlobalInvocationID.x;
  float p = in_[6 * i], w = in_[6 * i + 1];
  vec4 texel = vec4(in_[6 * i + 2], in_[6 * i + 3], in_[6 * i + 4], in_[6 * i + 5]);
  out_[5 * i + 0] = perlin_worley(p, w, SKYBAKE_REMAP_WORLEY_NEW_MIN);
  out_[5 * i + 1] = perlin_worley(p, w, SKYBAKE_REMAP_WORLEY_OLD_MIN);
  out_[5 * i + 2] = perlin_worley(p, w, SKYBAKE_REMAP_DILATE);
  out_[5 * i + 3] = pack_single_channel(texel, SKYBAKE_PACK_DILATE_BASE, shape_pack_weights());
  out_[5 * i + 4] = pack_single_channel(vec4(texel.rgb, 0.0), SKYBAKE_PACK_WEIGHTED_SUM,
                                        detail_pack_weights());
}
)",
                              in, 5);
  // The packed references come from pack_single_channel itself, on textures
  // holding the same texels.
  Texture shape(kPoints, 1, 1, 1, {"R", "G", "B", "A"});
  Texture detail(kPoints, 1, 1, 1, {"R", "G", "B"});
  for (int i = 0; i < kPoints; ++i)
    for (int c = 0; c < 4; ++c) {
      shape.at(i, 0, 0, 0, c) = t[4 * i + c];
      if (c < 3) detail.at(i, 0, 0, 0, c) = t[4 * i + c];
    }
  const Texture shape_packed = pack_single_channel(shape, shape_pack_weights());
  const Texture detail_packed = pack_single_channel(detail, detail_pack_weights());
  const PerlinWorleyRemap remaps[3] = {PerlinWorleyRemap::worley_new_min,
                                       PerlinWorleyRemap::worley_old_min,
                                       PerlinWorleyRemap::dilate};
  for (int i = 0; i < kPoints; ++i) {
    for (int r = 0; r < 3; ++r) {
      const float expected = perlin_worley(p[i], w[i], remaps[r]);
      ASSERT_NEAR(out[5 * i + r], expected, bar(expected)) << remap_name(remaps[r]) << " " << i;
    }
    ASSERT_NEAR(out[5 * i + 3], shape_packed.data[i], bar(shape_packed.data[i])) << i;
    ASSERT_NEAR(out[5 * i + 4], detail_packed.data[i], bar(detail_packed.data[i])) << i;
  }
}

TEST(CloudsDecode, WorleyWeightsAndCurlEncodingMatchCpp) {
  // Worley weights: every (octave, octaves) pair, exact (powers of two).
  std::vector<float> dummy(kPoints, 0.0f);
  const auto weights = run_points(R"(
void main() {
  uint i = gl_GlobalInvocationID.x;
  int octaves = int(i / 8u) % 8 + 1, octave = int(i % 8u);
  out_[i] = octave < octaves ? worley_fbm_weight(octave, octaves) : -1.0;
}
)",
                                  dummy, 1);
  for (int i = 0; i < 64; ++i) {
    const int octaves = i / 8 + 1, octave = i % 8;
    if (octave < octaves) {
      EXPECT_EQ(weights[i], worley_fbm_weight(octave, octaves)) << i;
    }
  }
  // Curl: decode of texels in [0, 1] and encode of values in [-1.2, 1.2]
  // scales, with scales 0.5 .. 20.
  const auto c = uniform_points(kPoints, 0.0f, 1.0f, 4);
  const auto v = uniform_points(kPoints, -12.0f, 12.0f, 5);
  const auto s = uniform_points(kPoints, 0.5f, 20.0f, 6);
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) in.insert(in.end(), {c[i], v[i], s[i]});
  const auto out = run_points(R"(
void main() {
  uint i = gl_GlobalInvocationID.x;
  out_[2 * i] = curl_value_from_texel(in_[3 * i], in_[3 * i + 2]);
  out_[2 * i + 1] = curl_texel_from_value(in_[3 * i + 1], in_[3 * i + 2]);
}
)",
                              in, 2);
  for (int i = 0; i < kPoints; ++i) {
    const float decoded = curl_value_from_texel(c[i], s[i]);
    const float encoded = curl_texel_from_value(v[i], s[i]);
    ASSERT_NEAR(out[2 * i], decoded, bar(decoded)) << i;
    ASSERT_NEAR(out[2 * i + 1], encoded, bar(encoded)) << i;
  }
}

TEST(CloudsDecode, WeatherAndHeightFunctionsMatchCpp) {
  const auto cov = uniform_points(kPoints, 0.0f, 1.0f, 7);
  const auto rain = uniform_points(kPoints, 0.0f, 1.0f, 8);
  const auto type = uniform_points(kPoints, 0.0f, 1.0f, 9);
  const auto h = uniform_points(kPoints, -0.1f, 1.1f, 10);
  const std::vector<CloudTypeProfile> types = default_cloud_types();
  std::vector<float> in;
  for (int i = 0; i < kPoints; ++i) {
    in.insert(in.end(), {cov[i], rain[i], type[i], h[i]});
    // Rain on a quarter of the points exactly (p = 1), none on another quarter.
    if (i % 4 == 0) in[in.size() - 3] = 1.0f;
    if (i % 4 == 1) in[in.size() - 3] = 0.0f;
  }
  std::string ramps = "const vec4 kRamp[4] = vec4[4](";
  std::string erosion = "const vec2 kErosion[4] = vec2[4](";
  for (int k = 0; k < 4; ++k) {
    const HeightRamp& r = types[k].density;
    ramps += "vec4(" + std::to_string(r.a) + ", " + std::to_string(r.b) + ", " +
             std::to_string(r.c) + ", " + std::to_string(r.d) + ")" + (k < 3 ? ", " : ");\n");
    erosion += "vec2(" + std::to_string(types[k].erosion_base) + ", " +
               std::to_string(types[k].erosion_top) + ")" + (k < 3 ? ", " : ");\n");
  }
  const auto out = run_points(ramps + erosion + R"(
void main() {
  uint i = gl_GlobalInvocationID.x;
  float c = in_[4 * i], p = in_[4 * i + 1], t = in_[4 * i + 2], h = in_[4 * i + 3];
  int k = int(i % 4u);
  out_[8 * i + 0] = coverage_with_rain(c, p);
  out_[8 * i + 1] = type_with_rain(t, p);
  out_[8 * i + 2] = frostbite_type_index(t, p);
  out_[8 * i + 3] = type_index_from_schneider(type_with_rain(t, p), p);
  out_[8 * i + 4] = index_from_type_u(type_u_from_index(3.0 * t, 7), 7);
  out_[8 * i + 5] = row_from_height(height_from_row(int(i % 128u), 128), 128);
  out_[8 * i + 6] = compute_height_density(kRamp[k], h);
  out_[8 * i + 7] = compute_height_erosion(kRamp[k], kErosion[k], h);
}
)",
                              in, 8);
  for (int i = 0; i < kPoints; ++i) {
    const float c = in[4 * i], p = in[4 * i + 1], t = in[4 * i + 2], hh = in[4 * i + 3];
    const int k = i % 4;
    const double expected[8] = {coverage_with_rain(c, p),
                                type_with_rain(t, p),
                                frostbite_type_index(t, p),
                                frostbite_type_index(t, p),
                                index_from_type_u(type_u_from_index(3.0 * t, 7), 7),
                                row_from_height(height_from_row(i % 128, 128), 128),
                                compute_height_density(types[k].density, hh),
                                compute_height_erosion(types[k], hh)};
    for (int j = 0; j < 8; ++j)
      ASSERT_NEAR(out[8 * i + j], expected[j], bar(expected[j])) << "point " << i << " value " << j;
    if (p == 1.0f) {
      ASSERT_EQ(out[8 * i + 3], 3.0f) << "raining: cumulonimbus exactly";
    }
  }
}

}  // namespace
}  // namespace skybake::gltest

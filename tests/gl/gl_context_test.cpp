// Smoke tests of the headless GL context (gl_context.hpp): the context is
// OpenGL 4.5 core on llvmpipe, a compute program runs and writes a buffer,
// textures uploaded from a Texture and from a DDS file's bytes read back the
// values put in (against our own DDS reader's decoding), and linear filtering
// follows the texel-centre convention. When the context cannot be opened
// these tests fail with the EGL step that failed; they never skip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "gl/gl_context.hpp"
#include "core/texture_sampling.hpp"
#include "io/dds.hpp"
#include "support/run.hpp"

namespace skybake::gltest {
namespace {

TEST(GlContext, OpensOpenGl45CoreOnLlvmpipe) {
  GlContext& gl = GlContext::shared();
  EXPECT_GE(gl.major_version() * 10 + gl.minor_version(), 45) << gl.version();
  EXPECT_NE(gl.version().find("Core Profile"), std::string::npos) << gl.version();
  // docs/runtime.md measures llvmpipe's filtering; another rasterizer would
  // need its own measurement.
  EXPECT_NE(gl.renderer().find("llvmpipe"), std::string::npos) << gl.renderer();
}

TEST(GlContext, ComputeProgramWritesStorageBuffer) {
  GlContext::shared();
  ComputeProgram program = compile_compute({}, R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { float values[]; };
uniform float scale;
void main() {
  uint i = gl_GlobalInvocationID.x;
  values[i] = scale * float(i) + 0.5;
}
)");
  program.set("scale", 0.25f);
  StorageBuffer out(256 * sizeof(float));
  out.bind(0);
  dispatch(program, 4);
  const std::vector<float> v = out.read_floats();
  ASSERT_EQ(v.size(), 256u);
  for (int i = 0; i < 256; ++i) EXPECT_EQ(v[i], 0.25f * float(i) + 0.5f) << i;
}

TEST(GlContext, CompileErrorNamesTheLineAndTheLog) {
  GlContext::shared();
  try {
    compile_compute({}, "layout(local_size_x = 1) in;\nvoid main() { undefined_name = 1.0; }\n");
    FAIL() << "a shader with an undefined name compiled";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("does not compile"), std::string::npos) << what;
    EXPECT_NE(what.find("undefined_name"), std::string::npos) << what;
    EXPECT_NE(what.find("3: void main()"), std::string::npos) << what;  // numbered source
  }
}

// Reads every texel of a 2D, 2D-array or 3D texture with texelFetch into
// out[((slice * h + y) * w + x) * 4 + c].
std::vector<float> fetch_all(const GlTexture& tex, const std::string& sampler, int w, int h,
                             int slices) {
  const std::string coord = sampler == "sampler2D" ? "ivec2(x, y)" : "ivec3(x, y, s)";
  ComputeProgram program = compile_compute({}, R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec4 texels[]; };
layout(binding = 0) uniform )" + sampler + R"( tex;
uniform int w;
uniform int h;
void main() {
  int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  int s = int(gl_GlobalInvocationID.z);
  texels[(s * h + y) * w + x] = texelFetch(tex, )" + coord + R"(, 0);
}
)");
  program.set("w", w);
  program.set("h", h);
  StorageBuffer out(size_t(w) * h * slices * 4 * sizeof(float));
  out.bind(0);
  tex.bind(0);
  dispatch(program, unsigned(w), unsigned(h), unsigned(slices));
  return out.read_floats();
}

Texture ramp_texture(int w, int h, int depth, int layers, int channels) {
  static const char* names[] = {"R", "G", "B", "A"};
  Texture t(w, h, depth, layers, std::vector<std::string>(names, names + channels));
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(0.03 * double(i % 29) + 0.01 * double(i / 29));
  return t;
}

TEST(GlContext, UploadedTextureReadsBackExactly) {
  GlContext::shared();
  const Texture t = ramp_texture(5, 3, 1, 1, 3);
  const GlTexture tex = upload_texture(t, {Filter::nearest});
  const std::vector<float> got = fetch_all(tex, "sampler2D", 5, 3, 1);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(got[(y * 5 + x) * 4 + c], t.at(x, y, 0, 0, c));
}

// Linear filtering at texel centres returns the texel; halfway between two
// texels, their mean (the convention of docs/architecture.md "Texel centres").
TEST(GlContext, LinearFilterFollowsTexelCentres) {
  GlContext::shared();
  Texture t(4, 1, 1, 1, {"R"});
  t.data = {1.0f, 3.0f, 7.0f, 15.0f};
  const GlTexture tex = upload_texture(t, {Filter::linear});
  ComputeProgram program = compile_compute({}, R"(
layout(local_size_x = 8) in;
layout(std430, binding = 0) buffer Out { float values[]; };
layout(binding = 0) uniform sampler2D tex;
void main() {
  uint i = gl_GlobalInvocationID.x;
  // i = 0..3: the centres; 4..6: halfway between neighbours; 7: the left edge.
  float u = i < 4u ? (float(i) + 0.5) / 4.0 : i < 7u ? float(i - 3u) / 4.0 : 0.0;
  values[i] = textureLod(tex, vec2(u, 0.5), 0.0).r;
}
)");
  StorageBuffer out(8 * sizeof(float));
  out.bind(0);
  tex.bind(0);
  dispatch(program, 1);
  const std::vector<float> v = out.read_floats();
  const float expected[] = {1, 3, 7, 15, 2, 5, 11, 1};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(v[i], expected[i]) << i;
}

// A DDS file's bytes uploaded as they are read back what our DDS reader
// decodes from the same file, level 0 of every layer or slice, with mips
// after it (so the offsets of the layout are exercised).
void expect_dds_round_trip(const Texture& level0, DdsFormat format, bool mips,
                           const std::string& name) {
  std::vector<Texture> chain = {level0};
  if (mips) {
    Texture next = level0;
    next.width = std::max(1, level0.width / 2);
    next.height = std::max(1, level0.height / 2);
    next.depth = std::max(1, level0.depth / 2);
    next.data.assign(next.texel_count() * size_t(next.channel_count()), 0.5f);
    chain.push_back(next);
  }
  const std::string path = test::scratch_file("gl", "dds_upload", name + ".dds");
  write_dds(path, chain, format);
  const Texture decoded = read_dds(path).mips[0];
  const GlTexture tex = upload_dds(path, {Filter::nearest});
  const std::string sampler = level0.is_volume() ? "sampler3D" : level0.is_array() ? "sampler2DArray" : "sampler2D";
  const int slices = level0.is_volume() ? level0.depth : level0.layers;
  const std::vector<float> got = fetch_all(tex, sampler, level0.width, level0.height, slices);
  const int components = dds_component_count(format);
  const bool unorm = format == DdsFormat::R8G8B8A8_UNORM || format == DdsFormat::R8G8_UNORM ||
                     format == DdsFormat::R8_UNORM;
  for (int s = 0; s < slices; ++s)
    for (int y = 0; y < level0.height; ++y)
      for (int x = 0; x < level0.width; ++x)
        for (int c = 0; c < components; ++c) {
          const int z = level0.is_volume() ? s : 0, layer = level0.is_volume() ? 0 : s;
          const size_t i = ((size_t(s) * level0.height + y) * level0.width + x) * 4 + c;
          // UNORM: GL converts c / 255 its own way (llvmpipe multiplies by
          // 1/255), one float ulp from our reader's division.
          ASSERT_NEAR(got[i], decoded.at(x, y, z, layer, c), unorm ? 1.2e-7 : 0.0)
              << name << " texel (" << x << ", " << y << ", " << s << ") channel " << c;
        }
}

TEST(GlContext, DdsBytesUploadAsTheyAre) {
  GlContext::shared();
  expect_dds_round_trip(ramp_texture(6, 4, 1, 1, 4), DdsFormat::R32G32B32A32_FLOAT, false, "rgba32f");
  expect_dds_round_trip(ramp_texture(6, 4, 1, 3, 4), DdsFormat::R16G16B16A16_FLOAT, true, "rgba16f_array");
  expect_dds_round_trip(ramp_texture(4, 4, 4, 1, 3), DdsFormat::R11G11B10_FLOAT, true, "r11g11b10_volume");
  expect_dds_round_trip(ramp_texture(5, 3, 1, 2, 4), DdsFormat::R8G8B8A8_UNORM, true, "rgba8_array");
  expect_dds_round_trip(ramp_texture(7, 5, 1, 1, 1), DdsFormat::R16_FLOAT, true, "r16f");
  expect_dds_round_trip(ramp_texture(3, 3, 3, 1, 1), DdsFormat::R8_UNORM, false, "r8_volume");
  expect_dds_round_trip(ramp_texture(5, 3, 1, 1, 2), DdsFormat::R8G8_UNORM, true, "rg8");
}

// Block-compressed DDS files uploaded as they are: Mesa's S3TC and RGTC
// decoders against ours (io/block_compression.hpp, exact rationals from the
// specifications). Mesa decodes to 8 bits (565 endpoints widened by bit
// replication, palette entries rounded to 8 bits), which moves a texel by
// up to 1.2 8-bit steps (measured); the bar is 1.5.
TEST(GlContext, BlockCompressedDdsUploadsAsTheyAre) {
  GlContext::shared();
  const double kBar = 1.5 / 255.0;
  for (const DdsFormat f : {DdsFormat::BC1_UNORM, DdsFormat::BC3_UNORM, DdsFormat::BC4_UNORM,
                            DdsFormat::BC5_UNORM}) {
    const int channels = dds_component_count(f) == 3 ? 3 : dds_component_count(f);
    // 10 x 6: blocks cut by the edge; 2 layers; mips down to 1 x 1 padded blocks.
    Texture level0 = ramp_texture(10, 6, 1, 2, channels);
    for (size_t i = 0; i < level0.data.size(); ++i)
      level0.data[i] = std::min(1.0f, std::max(0.0f, level0.data[i] * 0.9f));
    std::vector<Texture> chain = {level0};
    for (int w = 5, h = 3; w >= 1; w /= 2, h = std::max(1, h / 2)) {
      Texture next(w, h, 1, 2, level0.channels);
      std::fill(next.data.begin(), next.data.end(), 0.25f);
      chain.push_back(next);
      if (w == 1) break;
    }
    const std::string name = dxgi_format_name(f);
    const std::string path = test::scratch_file("gl", "dds_upload", name + ".dds");
    write_dds(path, chain, f);
    const Texture decoded = read_dds(path).mips.at(0);
    const GlTexture tex = upload_dds(path, {Filter::nearest});
    const std::vector<float> got = fetch_all(tex, "sampler2DArray", 10, 6, 2);
    double worst = 0.0;
    for (int s = 0; s < 2; ++s)
      for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 10; ++x)
          for (int c = 0; c < decoded.channel_count(); ++c) {
            const size_t i = ((size_t(s) * 6 + y) * 10 + x) * 4 + c;
            worst = std::max(worst, std::abs(double(got[i]) - decoded.at(x, y, 0, s, c)));
          }
    std::printf("[ measured ] %s: Mesa against our decoder, max %.3g (%.2f 8-bit steps)\n",
                name.c_str(), worst, worst * 255.0);
    EXPECT_LE(worst, kBar) << name;
  }
}


// llvmpipe's bilinear filter against the exact one (core/texture_sampling:
// double weights) at float texture coordinates, on a texture whose
// neighbouring texels differ by O(1): the error is the filter's weight
// resolution. docs/runtime.md "Precision" quotes the numbers printed here.
TEST(GlContext, LinearFilterWeightResolution) {
  GlContext::shared();
  for (const int n : {16, 64, 256}) {
    Texture t(n, n, 1, 1, {"R"});
    for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float((i * 7919u) % 13u) / 13.0f;
    const GlTexture tex = upload_texture(t, {Filter::linear});
    const int count = 1 << 16;
    std::vector<float> uv(size_t(count) * 2);
    for (int i = 0; i < count; ++i) {
      uv[2 * i] = float((i * 0.6180339887498949) - std::floor(i * 0.6180339887498949));
      uv[2 * i + 1] = float((i * 0.7548776662466927) - std::floor(i * 0.7548776662466927));
    }
    StorageBuffer in(uv);
    StorageBuffer out(size_t(count) * sizeof(float));
    ComputeProgram program = compile_compute({}, R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { vec2 uv[]; };
layout(std430, binding = 1) writeonly buffer Out { float values[]; };
layout(binding = 0) uniform sampler2D tex;
void main() {
  uint i = gl_GlobalInvocationID.x;
  values[i] = textureLod(tex, uv[i], 0.0).r;
}
)");
    in.bind(0);
    out.bind(1);
    tex.bind(0);
    dispatch(program, unsigned(count / 64));
    const std::vector<float> v = out.read_floats();
    double worst = 0.0;
    for (int i = 0; i < count; ++i)
      worst = std::max(worst, std::abs(v[i] - sample_bilinear(t, uv[2 * i], uv[2 * i + 1], 0, 0, false).x));
    std::printf("[ measured ] bilinear on %dx%d: max |GL - exact| %.3g (texel steps up to 1)\n", n, n, worst);
    EXPECT_LE(worst, 1e-6) << n;
  }
}
// The HLSL path: glslang's HLSL front end to SPIR-V, loaded through
// GL_ARB_gl_spirv, registers as bindings, a Texture and its SamplerState
// read as one combined sampler; a compile error names the line.
TEST(GlContext, HlslComputeProgramRunsThroughSpirv) {
  Texture t(2, 1, 1, 1, {"R"});
  t.data = {1.0f, 3.0f};
  const GlTexture tex = upload_texture(t, {Filter::linear});
  const ComputeProgram program = compile_compute_hlsl({}, R"(
Texture2D<float4> tex : register(t0);
SamplerState tex_sampler : register(s0);
RWStructuredBuffer<float4> values : register(u3);
[numthreads(4, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  float u = 0.25 + 0.5 * float(id.x) / 3.0;
  values[id.x] = float4(tex.SampleLevel(tex_sampler, float2(u, 0.5), 0.0).r, atan2(1.0, -1.0), 0.0, 0.0);
}
)");
  StorageBuffer out(4 * 4 * sizeof(float));
  out.bind(3);
  tex.bind(0);
  dispatch(program, 1);
  const std::vector<float> v = out.read_floats();
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(v[4 * i], 1.0f + 2.0f * float(i) / 3.0f, 1e-6) << i;
    EXPECT_NEAR(v[4 * i + 1], 3.0f * 3.14159265f / 4.0f, 1e-5) << i;
  }
  try {
    compile_compute_hlsl({}, "[numthreads(1, 1, 1)]\nvoid main() { undefined_name = 1.0; }\n");
    FAIL() << "an HLSL shader with an undefined name compiled";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("undefined_name"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace skybake::gltest

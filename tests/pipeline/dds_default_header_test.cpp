// The DDS header an output gets (pipeline/dds_output.hpp output_dds_header):
// dds_default_header of its format when the preset names none (legacy for
// the 8-bit and block formats a legacy header describes, DX10 for float,
// R8G8 and 2D arrays), dds_header forcing either. The default files of a
// real bake are opened with two independent readers, Pillow (Debian
// python3-pil) and OpenImageIO, and their texels compared with our reader's
// (docs/formats.md "Which tools read which file": both read only the first
// slice of a volume, so only that slice is compared).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/dds.hpp"
#include "pipeline/dds_output.hpp"
#include "support/pillow.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

OutputSpec spec_with(nlohmann::json options) {
  OutputSpec spec;
  spec.product = "noise_shape";
  spec.name = "noise_shape";
  spec.formats = {"dds"};
  spec.options = std::move(options);
  return spec;
}

TEST(DdsDefaultHeader, OutputTakesTheFormatsDefaultUnlessDdsHeaderSaysOtherwise) {
  const OutputSpec none = spec_with(nlohmann::json::object());
  EXPECT_EQ(output_dds_header(none, DdsFormat::BC3_UNORM, 1), DdsHeader::legacy);
  EXPECT_EQ(output_dds_header(none, DdsFormat::R8G8B8A8_UNORM, 1), DdsHeader::legacy);
  EXPECT_EQ(output_dds_header(none, DdsFormat::R8G8B8A8_UNORM, 8), DdsHeader::dx10);
  EXPECT_EQ(output_dds_header(none, DdsFormat::R8G8_UNORM, 1), DdsHeader::dx10);
  EXPECT_EQ(output_dds_header(none, DdsFormat::R32G32B32A32_FLOAT, 1), DdsHeader::dx10);
  const OutputSpec dx10 = spec_with({{"dds_header", "dx10"}});
  EXPECT_EQ(output_dds_header(dx10, DdsFormat::BC3_UNORM, 1), DdsHeader::dx10);
  const OutputSpec legacy = spec_with({{"dds_header", "legacy"}});
  EXPECT_EQ(output_dds_header(legacy, DdsFormat::R32G32B32A32_FLOAT, 1), DdsHeader::legacy);
  EXPECT_EQ(output_dds_header(legacy, DdsFormat::R8G8_UNORM, 1), DdsHeader::legacy);
}

// Two scenes of small cloud textures and one float table, every header left
// to its default except one forced to DX10.
fs::path write_presets(const fs::path& dir) {
  const nlohmann::json worley = {{{"period", 2}, {"octaves", 2}},
                                 {{"period", 2}, {"octaves", 2}},
                                 {{"period", 4}, {"octaves", 1}}};
  const nlohmann::json shape = {
      {"product", "noise_shape"}, {"size", {16, 16, 16}}, {"formats", {"dds"}},
      {"dds_format", "BC3_UNORM"}, {"perlin", {{"period", 4}, {"octaves", 2}}},
      {"perlin_worley", {{"period", 4}, {"octaves", 2}}}, {"worley", worley}};
  const nlohmann::json a = {
      {"name", "a"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", test::source_path("presets/atmospheres/earth.json").string()},
      {"clouds", test::source_path("presets/clouds/storm.json").string()},
      {"outputs",
       {{{"product", "weather"}, {"size", {32, 32}}, {"formats", {"dds"}}},
        {{"product", "cloud_types"}, {"size", {16}}, {"type_width", 8}, {"formats", {"dds"}},
         {"dds_format", "BC5_UNORM"}},
        shape,
        {{"product", "noise_detail"}, {"size", {16, 16, 16}}, {"formats", {"dds"}},
         {"pack", "single_channel"}, {"worley", worley}},
        {{"product", "curl"}, {"size", {16, 16}}, {"formats", {"dds"}}, {"channels", "rg"},
         {"period", 2}, {"octaves", 2}},
        {{"product", "transmittance"}, {"size", {16, 8}}, {"formats", {"dds"}}}}}};
  const nlohmann::json b = {
      {"name", "b"},
      {"clouds", test::source_path("presets/clouds/storm.json").string()},
      {"outputs",
       {{{"product", "weather"}, {"size", {32, 32}}, {"formats", {"dds"}},
         {"dds_format", "BC1_UNORM"}},
        {{"product", "noise_detail"}, {"size", {16, 16, 16}}, {"formats", {"dds"}},
         {"pack", "single_channel"}, {"dds_format", "BC4_UNORM"}, {"dds_header", "dx10"},
         {"worley", worley}}}}};
  fs::create_directories(dir / "presets");
  std::ofstream(dir / "presets" / "a.json") << a.dump(2);
  std::ofstream(dir / "presets" / "b.json") << b.dump(2);
  return dir / "presets";
}

// Our reader's texels of level 0, slice 0, in the format's components.
struct Ours {
  int width, height, components;
  std::vector<float> values;  // components per texel
};

Ours ours(const fs::path& file) {
  const DdsImage image = read_dds(file.string());
  const Texture& t = image.mips.at(0);
  Ours o{t.width, t.height, dds_component_count(image.format), {}};
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x)
      for (int c = 0; c < o.components; ++c) o.values.push_back(t.texel(x, y, 0)[c]);
  return o;
}

// Within `steps` 8-bit steps: Pillow and OpenImageIO decode the block
// formats to 8 bits with their own integer rounding; uncompressed 8-bit
// texels are the same bytes (1e-3: the float rounding of k / 255).
double tolerance_steps(DdsFormat format) {
  return dds_is_block_compressed(format) ? 2.0 : 1e-3;
}

void expect_pillow_reads(const fs::path& file, DdsFormat format) {
  SCOPED_TRACE("Pillow " + file.string());
  const test::PillowImage pil = test::pillow_read(file.string());
  const Ours o = ours(file);
  ASSERT_EQ(pil.width, o.width);
  ASSERT_EQ(pil.height, o.height);
  const int n = int(pil.mode.size());  // "L", "RGB", "RGBA": one letter per byte
  ASSERT_GE(n, o.components) << pil.mode;
  ASSERT_EQ(pil.bytes.size(), size_t(o.width) * o.height * n);
  for (int t = 0; t < o.width * o.height; ++t)
    for (int c = 0; c < o.components; ++c)
      ASSERT_NEAR(pil.bytes[size_t(t) * n + c], o.values[size_t(t) * o.components + c] * 255.0,
                  tolerance_steps(format))
          << "texel " << t << " channel " << c;
}

void expect_oiio_reads(const fs::path& file, DdsFormat format) {
  SCOPED_TRACE("OpenImageIO " + file.string());
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  const Ours o = ours(file);
  ASSERT_EQ(spec.width, o.width);
  ASSERT_EQ(spec.height, o.height);
  ASSERT_GE(spec.nchannels, o.components);
  std::vector<float> got(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_scanlines(0, 0, 0, spec.height, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                                 got.data()))
      << in->geterror();
  for (int t = 0; t < o.width * o.height; ++t)
    for (int c = 0; c < o.components; ++c)
      ASSERT_NEAR(got[size_t(t) * spec.nchannels + c] * 255.0,
                  o.values[size_t(t) * o.components + c] * 255.0, tolerance_steps(format))
          << "texel " << t << " channel " << c;
}

TEST(DdsDefaultHeader, DefaultFilesOfABakeOpenInPillowAndOpenImageIO) {
  const fs::path dir = test::fresh_dir("dds_default_header");
  const fs::path presets = write_presets(dir);
  const test::RunResult r =
      test::run_skybake({"bake", presets.string(), "--out", (dir / "out").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  struct Expect {
    const char* file;
    DdsFormat format;
    DdsHeader header;
  };
  const Expect expected[] = {
      {"a/weather.dds", DdsFormat::R8G8B8A8_UNORM, DdsHeader::legacy},
      {"a/cloud_types.dds", DdsFormat::BC5_UNORM, DdsHeader::legacy},
      {"a/noise_shape.dds", DdsFormat::BC3_UNORM, DdsHeader::legacy},
      {"a/noise_detail.dds", DdsFormat::R8_UNORM, DdsHeader::legacy},
      {"b/weather.dds", DdsFormat::BC1_UNORM, DdsHeader::legacy},
      // What legacy cannot describe well, or what the preset forces.
      {"a/curl.dds", DdsFormat::R8G8_UNORM, DdsHeader::dx10},
      {"a/transmittance.dds", DdsFormat::R32G32B32A32_FLOAT, DdsHeader::dx10},
      {"b/noise_detail.dds", DdsFormat::BC4_UNORM, DdsHeader::dx10},
  };
  for (const Expect& e : expected) {
    SCOPED_TRACE(e.file);
    const fs::path file = dir / "out" / e.file;
    const DdsImage image = read_dds(file.string());
    EXPECT_EQ(image.format, e.format);
    EXPECT_EQ(image.header, e.header);
    if (e.header != DdsHeader::legacy) continue;
    expect_pillow_reads(file, e.format);
    expect_oiio_reads(file, e.format);
  }
}

}  // namespace
}  // namespace skybake

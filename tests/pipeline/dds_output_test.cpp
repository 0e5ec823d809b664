// DDS outputs (pipeline/dds_output.hpp): the format an output writes (unorm8
// by channel count, float by precision, dds_format as given), the block
// formats each 8-bit product accepts, and a whole bake of block-compressed
// and legacy-header outputs: the files hold what the options say, every mip
// level, read back through `skybake check-tiling`, and are byte-identical for
// 1 and 2 threads (mip chains and block encoding run in parallel).
#include "pipeline/dds_output.hpp"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/dds.hpp"
#include "support/file_bytes.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

OutputSpec spec_of(const std::string& product, nlohmann::json options) {
  OutputSpec spec;
  spec.product = product;
  spec.name = product;
  spec.formats = {"dds"};
  options["product"] = product;
  spec.options = std::move(options);
  return spec;
}

const ProductInfo& product(const std::string& name) {
  const ProductInfo* info = find_product(name);
  EXPECT_NE(info, nullptr) << name;
  return *info;
}

TEST(DdsOutput, Unorm8PicksTheFormatByChannelCount) {
  const OutputSpec spec = spec_of("noise_shape", nlohmann::json::object());
  const ProductInfo& info = product("noise_shape");
  EXPECT_EQ(output_dds_format(spec, info, 1), DdsFormat::R8_UNORM);
  EXPECT_EQ(output_dds_format(spec, info, 2), DdsFormat::R8G8_UNORM);
  EXPECT_EQ(output_dds_format(spec, info, 3), DdsFormat::R8G8B8A8_UNORM);
  EXPECT_EQ(output_dds_format(spec, info, 4), DdsFormat::R8G8B8A8_UNORM);
}

TEST(DdsOutput, FloatTablesFollowPrecisionAndDdsFormatWins) {
  OutputSpec spec = spec_of("transmittance", nlohmann::json::object());
  const ProductInfo& info = product("transmittance");
  EXPECT_EQ(output_dds_format(spec, info, 3), DdsFormat::R32G32B32A32_FLOAT);
  spec.precision = "half";
  EXPECT_EQ(output_dds_format(spec, info, 3), DdsFormat::R16G16B16A16_FLOAT);
  EXPECT_EQ(output_dds_format(spec, info, 1), DdsFormat::R16_FLOAT);
  spec.options["dds_format"] = "R11G11B10_FLOAT";
  EXPECT_EQ(output_dds_format(spec, info, 3), DdsFormat::R11G11B10_FLOAT);
  EXPECT_EQ(output_dds_header(spec, DdsFormat::R11G11B10_FLOAT, 1), DdsHeader::dx10);
}

TEST(DdsOutput, EachEightBitProductTakesTheBlockFormatOfItsChannels) {
  struct Case {
    const char* product;
    nlohmann::json options;
    const char* fits;
  };
  const std::vector<Case> cases = {
      {"noise_shape", nlohmann::json::object(), "BC3_UNORM"},
      {"noise_shape", {{"pack", "single_channel"}}, "BC4_UNORM"},
      {"noise_detail", nlohmann::json::object(), "BC1_UNORM"},
      {"curl", nlohmann::json::object(), "BC1_UNORM"},
      {"curl", {{"channels", "rg"}}, "BC5_UNORM"},
      {"weather", nlohmann::json::object(), "BC1_UNORM"},
      {"weather", {{"layout", "frostbite"}}, "BC5_UNORM"},
      {"cloud_types", nlohmann::json::object(), "BC5_UNORM"},
      {"height_gradients", nlohmann::json::object(), "BC3_UNORM"},
      {"cirrus", nlohmann::json::object(), "BC1_UNORM"},
  };
  for (const Case& c : cases) {
    for (const char* bc : {"BC1_UNORM", "BC3_UNORM", "BC4_UNORM", "BC5_UNORM"}) {
      nlohmann::json options = c.options;
      options["dds_format"] = bc;
      options["dds_header"] = "legacy";  // every block format has one
      const std::vector<ProductProblem> problems =
          dds_output_problems(spec_of(c.product, options), product(c.product));
      if (std::string(bc) == c.fits) {
        EXPECT_TRUE(problems.empty()) << c.product << " " << c.options << " " << bc << ": "
                                      << problems.front().rule;
      } else {
        ASSERT_EQ(problems.size(), 1u) << c.product << " " << c.options << " " << bc;
        EXPECT_EQ(problems[0].pointer, "/dds_format");
      }
    }
  }
}

// ---- a whole bake ------------------------------------------------------------

// Cloud textures in block formats (legacy headers by default, one forced to
// DX10), curl in R8G8 through unorm8 (DX10 by default) and a BC4 volume with
// a legacy header asked for, small enough for a test.
fs::path write_preset(const fs::path& dir) {
  const nlohmann::json preset = {
      {"name", "bc"},
      {"clouds", test::source_path("presets/clouds/storm.json").string()},
      {"outputs",
       {{{"product", "noise_shape"}, {"size", {32, 32, 32}}, {"formats", {"dds"}},
         {"dds_format", "BC3_UNORM"},
         {"perlin", {{"period", 4}, {"octaves", 2}}},
         {"perlin_worley", {{"period", 4}, {"octaves", 2}}},
         {"worley", {{{"period", 4}, {"octaves", 2}}, {{"period", 4}, {"octaves", 2}},
                     {{"period", 8}, {"octaves", 1}}}}},
        {{"product", "noise_detail"}, {"size", {16, 16, 16}}, {"formats", {"dds"}},
         {"pack", "single_channel"}, {"dds_format", "BC4_UNORM"}, {"dds_header", "legacy"},
         {"worley", {{{"period", 2}, {"octaves", 2}}, {{"period", 2}, {"octaves", 2}},
                     {{"period", 4}, {"octaves", 1}}}}},
        {{"product", "curl"}, {"size", {32, 32}}, {"formats", {"dds"}}, {"channels", "rg"},
         {"period", 2}, {"octaves", 2}},
        {{"product", "weather"}, {"size", {64, 64}}, {"formats", {"dds"}},
         {"dds_format", "BC1_UNORM"}, {"dds_header", "dx10"}},
        {{"product", "cloud_types"}, {"size", {16}}, {"formats", {"dds"}},
         {"dds_format", "BC5_UNORM"}, {"type_width", 4}}}}};
  fs::create_directories(dir);
  std::ofstream(dir / "bc.json") << preset.dump(2);
  return dir / "bc.json";
}

TEST(DdsOutputBake, BlockAndLegacyFilesAreWhatTheOptionsSayForOneAndTwoThreads) {
  const fs::path dir = test::fresh_dir("dds_output_bake");
  const fs::path preset = write_preset(dir);
  for (const char* threads : {"1", "2"}) {
    const test::RunResult r = test::run_skybake(
        {"bake", preset.string(), "--out", (dir / threads).string(), "--threads", threads});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  struct Expect {
    const char* file;
    DdsFormat format;
    DdsHeader header;
    size_t levels;
    int channels;
  };
  const Expect expected[] = {
      {"noise_shape.dds", DdsFormat::BC3_UNORM, DdsHeader::legacy, 6, 4},
      {"noise_detail.dds", DdsFormat::BC4_UNORM, DdsHeader::legacy, 5, 1},
      {"curl.dds", DdsFormat::R8G8_UNORM, DdsHeader::dx10, 6, 2},
      {"weather.dds", DdsFormat::BC1_UNORM, DdsHeader::dx10, 7, 4},
      {"cloud_types.dds", DdsFormat::BC5_UNORM, DdsHeader::legacy, 1, 2},
  };
  for (const Expect& e : expected) {
    SCOPED_TRACE(e.file);
    const fs::path one = dir / "1" / "bc" / e.file, two = dir / "2" / "bc" / e.file;
    EXPECT_EQ(test::read_bytes(one), test::read_bytes(two)) << "files differ between 1 and 2 threads";
    const DdsImage image = read_dds(one.string());
    EXPECT_EQ(image.format, e.format);
    EXPECT_EQ(image.header, e.header);
    EXPECT_EQ(image.mips.size(), e.levels);
    EXPECT_EQ(image.mips[0].channel_count(), e.channels);
  }
  EXPECT_EQ(test::read_bytes(dir / "1" / "bc" / "manifest.json"),
            test::read_bytes(dir / "2" / "bc" / "manifest.json"));
  // Our reader decodes the block files for check-tiling too.
  const test::RunResult tiling = test::run_skybake(
      {"check-tiling", (dir / "1" / "bc" / "noise_shape.dds").string(),
       (dir / "1" / "bc" / "noise_detail.dds").string()});
  EXPECT_NE(tiling.exit_code, 4) << tiling.out << tiling.err;
  EXPECT_EQ(tiling.err.find("error"), std::string::npos) << tiling.err;
}

}  // namespace
}  // namespace skybake

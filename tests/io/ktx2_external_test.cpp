// Our KTX2 files read by an independent reader: ktx-parse (npm, pinned in
// tests/js/package.json, installed by scripts/install-deps.sh) run under node
// by tests/js/ktx2_dump.mjs. What it reports is compared with what the KTX2
// and Data Format specifications say the file must hold, written out here by
// hand (not taken from src/io), and the level bytes with an encoding of the
// texture done here. The test fails when node or ktx-parse is missing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/half.hpp"
#include "core/mip_chain.hpp"
#include "io/block_compression.hpp"
#include "io/ktx2.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

using nlohmann::json;

// ktx-parse's view of `path`; fails the test (with the reason) when it cannot run.
json ktx_parse(const std::string& path) {
  const std::string script = test::source_path("tests/js/ktx2_dump.mjs").string();
  const std::string module =
      test::source_path("tests/js/node_modules/ktx-parse/package.json").string();
  int status = -1;
  test::run_shell("command -v node > /dev/null 2>&1", &status);
  if (status != 0) {
    ADD_FAILURE() << "node is not installed (scripts/install-deps.sh installs it)";
    return json();
  }
  if (FILE* f = std::fopen(module.c_str(), "r")) {
    std::fclose(f);
  } else {
    ADD_FAILURE() << "ktx-parse is not installed in tests/js/node_modules "
                     "(scripts/install-deps.sh runs npm ci there)";
    return json();
  }
  const std::string out = test::run_shell("node '" + script + "' '" + path + "' 2>&1", &status);
  if (status != 0) {
    ADD_FAILURE() << "ktx-parse failed on " << path << ": " << out;
    return json();
  }
  return json::parse(out);
}

// What the specifications say for each format (KTX2 "typeSize"; Data Format
// Specification 1.3, RGBSDA; Vulkan "Formats" for the codes).
struct Spec {
  Ktx2Format format;
  uint32_t vk_format, type_size;
  int components;
  bool unorm;
};
const Spec kSpecs[] = {
    {Ktx2Format::R8_UNORM, 9, 1, 1, true},
    {Ktx2Format::R8G8_UNORM, 16, 1, 2, true},
    {Ktx2Format::R8G8B8A8_UNORM, 37, 1, 4, true},
    {Ktx2Format::R16_SFLOAT, 76, 2, 1, false},
    {Ktx2Format::R16G16B16A16_SFLOAT, 97, 2, 4, false},
    {Ktx2Format::R32_SFLOAT, 100, 4, 1, false},
    {Ktx2Format::R32G32B32A32_SFLOAT, 109, 4, 4, false},
};

// Block-compressed formats (Data Format Specification 1.3, "BC1A", "BC3",
// "BC4", "BC5"; the channel ids of each model): 4x4 blocks, 64-bit samples.
struct BlockSpec {
  Ktx2Format format;
  BcFormat bc;
  uint32_t vk_format;
  int components, block_bytes, color_model;
  std::vector<std::pair<int, int>> samples;  // channel id, bit offset
};
const BlockSpec kBlockSpecs[] = {
    {Ktx2Format::BC1_RGB_UNORM_BLOCK, BcFormat::bc1, 131, 3, 8, 128, {{0, 0}}},
    {Ktx2Format::BC3_UNORM_BLOCK, BcFormat::bc3, 137, 4, 16, 130, {{15, 0}, {0, 64}}},
    {Ktx2Format::BC4_UNORM_BLOCK, BcFormat::bc4, 139, 1, 8, 131, {{0, 0}}},
    {Ktx2Format::BC5_UNORM_BLOCK, BcFormat::bc5, 141, 2, 16, 132, {{0, 0}, {1, 64}}},
};

// The level's bytes as the specification lays them out: layers, slices,
// rows, texels; components R, G, B, A little-endian; a missing component 0,
// a missing alpha 1.
std::string expected_hex(const Texture& m, const Spec& s) {
  std::string hex;
  const int nc = m.channel_count();
  for (size_t t = 0; t < m.texel_count(); ++t)
    for (int c = 0; c < s.components; ++c) {
      const float v = c < nc ? m.data[t * size_t(nc) + size_t(c)] : (c == 3 ? 1.0f : 0.0f);
      uint32_t bits = 0;
      if (s.unorm) {
        bits = uint32_t(std::lround(std::min(std::max(v, 0.0f), 1.0f) * 255.0f));
      } else if (s.type_size == 2) {
        bits = half_from_float(v);
      } else {
        std::memcpy(&bits, &v, 4);
      }
      for (uint32_t k = 0; k < s.type_size; ++k)
        hex += fmt::format("{:02x}", (bits >> (8 * k)) & 0xFF);
    }
  return hex;
}

Texture make(int w, int h, int d, int layers, int channels, size_t seed) {
  static const std::vector<std::string> names = {"R", "G", "B", "A"};
  Texture t(w, h, d, layers, {names.begin(), names.begin() + channels});
  for (size_t i = 0; i < t.data.size(); ++i)
    t.data[i] = float((i * 7 + seed * 13) % 256) / 255.0f;  // exact in every format
  return t;
}

void check_file(const Spec& s, int w, int h, int d, int layers, int channels, bool mips) {
  SCOPED_TRACE(fmt::format("{} {}x{}x{}x{} {} channels{}", ktx2_format_name(s.format), w, h, d,
                           layers, channels, mips ? " with mips" : ""));
  std::vector<Texture> levels;
  const int n = mips ? mip_count(w, h, d) : 1;
  for (int p = 0; p < n; ++p)
    levels.push_back(make(std::max(1, w >> p), std::max(1, h >> p), std::max(1, d >> p), layers,
                          channels, size_t(p)));
  levels[0].metadata["product"] = "transmittance";
  const std::string path = test::scratch_file(
      "io_ktx2_external", "files",
      fmt::format("{}_{}x{}x{}x{}_{}.ktx2", ktx2_format_name(s.format), w, h, d, layers, n));
  write_ktx2(path, levels, s.format);
  const json k = ktx_parse(path);
  if (k.is_null()) return;

  EXPECT_EQ(k["vkFormat"], s.vk_format);
  EXPECT_EQ(k["typeSize"], s.type_size);
  EXPECT_EQ(k["pixelWidth"], w);
  EXPECT_EQ(k["pixelHeight"], h);
  EXPECT_EQ(k["pixelDepth"], d > 1 ? d : 0);
  EXPECT_EQ(k["layerCount"], layers > 1 ? layers : 0);
  EXPECT_EQ(k["faceCount"], 1);
  EXPECT_EQ(k["levelCount"], n);
  EXPECT_EQ(k["supercompressionScheme"], 0);

  const json& dfd = k["dfd"];
  EXPECT_EQ(dfd["vendorId"], 0);
  EXPECT_EQ(dfd["descriptorType"], 0);
  EXPECT_EQ(dfd["versionNumber"], 2);
  EXPECT_EQ(dfd["colorModel"], 1);        // KHR_DF_MODEL_RGBSDA
  EXPECT_EQ(dfd["colorPrimaries"], 1);    // KHR_DF_PRIMARIES_BT709
  EXPECT_EQ(dfd["transferFunction"], 1);  // KHR_DF_TRANSFER_LINEAR
  EXPECT_EQ(dfd["flags"], 0);             // straight alpha
  EXPECT_EQ(dfd["texelBlockDimension"], json::array({0, 0, 0, 0}));
  EXPECT_EQ(dfd["bytesPlane"], json::array({s.components * int(s.type_size), 0, 0, 0, 0, 0, 0, 0}));
  ASSERT_EQ(dfd["samples"].size(), size_t(s.components));
  const int channel_ids[] = {0, 1, 2, 15};
  for (int c = 0; c < s.components; ++c) {
    const json& sample = dfd["samples"][size_t(c)];
    EXPECT_EQ(sample["bitOffset"], c * 8 * int(s.type_size)) << c;
    EXPECT_EQ(sample["bitLength"], 8 * int(s.type_size) - 1) << c;  // stored as length - 1
    // Float channels are FLOAT | SIGNED (0x80 | 0x40 in the channelType byte)
    // with -1.0f and 1.0f as bounds, which ktx-parse reads as int32 for signed samples.
    EXPECT_EQ(sample["channelType"], channel_ids[c] | (s.unorm ? 0 : 0xC0)) << c;
    EXPECT_EQ(sample["samplePosition"], json::array({0, 0, 0, 0})) << c;
    EXPECT_EQ(sample["sampleLower"], s.unorm ? 0 : int32_t(0xBF800000u)) << c;
    EXPECT_EQ(sample["sampleUpper"], s.unorm ? 255 : int32_t(0x3F800000u)) << c;
  }

  const json& kv = k["keyValue"];
  EXPECT_EQ(kv["KTXorientation"], d > 1 ? "rdi" : "rd");
  EXPECT_EQ(kv["KTXwriter"], "skybake " SKYBAKE_VERSION);
  EXPECT_EQ(json::parse(kv["skybake.channels"].get<std::string>()), json(levels[0].channels));
  EXPECT_EQ(kv["skybake.product"], "\"transmittance\"");

  ASSERT_EQ(k["levels"].size(), size_t(n));
  const int texel_bytes = s.components * int(s.type_size);
  const int align =
      texel_bytes % 4 == 0 ? texel_bytes : 4;  // lcm(texel bytes, 4) for 1, 2, 4, 8, 16
  for (int p = 0; p < n; ++p) {
    const json& level = k["levels"][size_t(p)];
    const Texture& m = levels[size_t(p)];
    const uint64_t bytes = uint64_t(m.texel_count()) * uint64_t(texel_bytes);
    EXPECT_EQ(level["byteLength"], bytes) << p;
    EXPECT_EQ(level["uncompressedByteLength"], bytes) << p;
    EXPECT_EQ(level["byteOffset"].get<uint64_t>() % uint64_t(align), 0u) << p;
    if (p + 1 < n) {  // smaller levels come first in the file
      EXPECT_LT(k["levels"][size_t(p + 1)]["byteOffset"].get<uint64_t>(),
                level["byteOffset"].get<uint64_t>())
          << p;
    }
    EXPECT_EQ(level["hex"], expected_hex(m, s)) << "level " << p;
  }
  EXPECT_EQ(
      k["levels"][0]["byteOffset"].get<uint64_t>() + k["levels"][0]["byteLength"].get<uint64_t>(),
      k["fileLength"].get<uint64_t>());
}

std::string hex_of(const std::vector<uint8_t>& bytes) {
  std::string hex;
  for (uint8_t b : bytes) hex += fmt::format("{:02x}", b);
  return hex;
}

void check_block_file(const BlockSpec& s, int w, int h, int d, int layers, int channels) {
  SCOPED_TRACE(fmt::format("{} {}x{}x{}x{} {} channels", ktx2_format_name(s.format), w, h, d,
                           layers, channels));
  std::vector<Texture> levels;
  const int n = mip_count(w, h, d);
  for (int p = 0; p < n; ++p)
    levels.push_back(make(std::max(1, w >> p), std::max(1, h >> p), std::max(1, d >> p), layers,
                          channels, size_t(p)));
  const std::string path = test::scratch_file(
      "io_ktx2_external", "blocks",
      fmt::format("{}_{}x{}x{}x{}.ktx2", ktx2_format_name(s.format), w, h, d, layers));
  write_ktx2(path, levels, s.format);
  const json k = ktx_parse(path);
  if (k.is_null()) return;
  EXPECT_EQ(k["vkFormat"], s.vk_format);
  EXPECT_EQ(k["typeSize"], 1);  // _BLOCK formats
  EXPECT_EQ(k["pixelDepth"], d > 1 ? d : 0);
  EXPECT_EQ(k["layerCount"], layers > 1 ? layers : 0);
  EXPECT_EQ(k["levelCount"], n);
  const json& dfd = k["dfd"];
  EXPECT_EQ(dfd["colorModel"], s.color_model);
  EXPECT_EQ(dfd["colorPrimaries"], 1);
  EXPECT_EQ(dfd["transferFunction"], 1);
  EXPECT_EQ(dfd["texelBlockDimension"], json::array({3, 3, 0, 0}));  // 4x4x1 blocks
  EXPECT_EQ(dfd["bytesPlane"], json::array({s.block_bytes, 0, 0, 0, 0, 0, 0, 0}));
  ASSERT_EQ(dfd["samples"].size(), s.samples.size());
  for (size_t i = 0; i < s.samples.size(); ++i) {
    const json& sample = dfd["samples"][i];
    EXPECT_EQ(sample["channelType"], s.samples[i].first) << i;
    EXPECT_EQ(sample["bitOffset"], s.samples[i].second) << i;
    EXPECT_EQ(sample["bitLength"], 63) << i;
    EXPECT_EQ(sample["sampleLower"], 0) << i;
    EXPECT_EQ(sample["sampleUpper"], 0xFFFFFFFFu) << i;
  }
  ASSERT_EQ(k["levels"].size(), size_t(n));
  for (int p = 0; p < n; ++p) {
    const Texture& m = levels[size_t(p)];
    const uint64_t blocks = uint64_t((m.width + 3) / 4) * uint64_t((m.height + 3) / 4);
    const json& level = k["levels"][size_t(p)];
    EXPECT_EQ(level["byteLength"], blocks * uint64_t(m.depth * m.layers * s.block_bytes)) << p;
    EXPECT_EQ(level["byteOffset"].get<uint64_t>() % uint64_t(s.block_bytes), 0u) << p;
    std::vector<uint8_t> want;  // each slice's blocks, layers then slices
    for (int layer = 0; layer < m.layers; ++layer)
      for (int z = 0; z < m.depth; ++z) {
        const std::vector<uint8_t> slice =
            encode_bc(m.texel(0, 0, z, layer), m.width, m.height, channels, s.bc);
        want.insert(want.end(), slice.begin(), slice.end());
      }
    EXPECT_EQ(level["hex"], hex_of(want)) << "level " << p;
  }
}

TEST(Ktx2External, KtxParseReadsBlockCompressedFilesAsTheSpecificationsSay) {
  for (const BlockSpec& s : kBlockSpecs) {
    check_block_file(s, 10, 6, 1, 1, s.components);
    check_block_file(s, 8, 8, 1, 2, 1);
    check_block_file(s, 4, 4, 3, 1, std::min(s.components, 2));
  }
}

TEST(Ktx2External, KtxParseReadsEveryFormatAndShapeAsTheSpecificationsSay) {
  for (const Spec& s : kSpecs) {
    check_file(s, 7, 5, 1, 1, s.components, false);
    check_file(s, 8, 4, 1, 1, std::min(s.components, 3), true);  // RGB in RGBA: alpha 1
    check_file(s, 4, 4, 1, 3, 1, true);                          // 2D array
    check_file(s, 4, 2, 6, 1, 1, true);                          // 3D
  }
}

// A cube map and a cube array (write_ktx2_cube): faceCount 6, layerCount
// the cubes (0 for one), each level's faces in order, as ktx-parse reads them.
TEST(Ktx2External, CubeMapsReadAsSixFaces) {
  const Spec& half = kSpecs[4];
  ASSERT_EQ(half.format, Ktx2Format::R16G16B16A16_SFLOAT);
  for (int cubes : {1, 2}) {
    std::vector<Texture> levels = {make(8, 8, 1, 6 * cubes, 3, 1), make(4, 4, 1, 6 * cubes, 3, 2)};
    const std::string path = test::scratch_file("io_ktx2_external", "files",
                                                fmt::format("cube_{}.ktx2", cubes));
    write_ktx2_cube(path, {&levels[0], &levels[1]}, half.format);
    const json k = ktx_parse(path);
    if (k.is_null()) return;
    EXPECT_EQ(k["faceCount"], 6);
    EXPECT_EQ(k["layerCount"], cubes > 1 ? cubes : 0);
    EXPECT_EQ(k["pixelDepth"], 0);
    ASSERT_EQ(k["levels"].size(), 2u);
    for (size_t p = 0; p < 2; ++p)
      EXPECT_EQ(k["levels"][p]["hex"], expected_hex(levels[p], half)) << cubes << " " << p;
  }
}

}  // namespace
}  // namespace skybake

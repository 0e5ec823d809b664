// Tests for io/exr: every shape is read back twice, with plain OpenImageIO
// calls (pixels by channel name, header attributes, part names) that share no
// code with read_exr, and through read_exr itself. Plus half rounding,
// determinism and refusal of non-finite values.
#include "io/exr.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <utility>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;

std::string tmp_path(const std::string& name, const std::string& file) {
  return skybake::test::scratch_file("io_exr", name, file);
}

// Distinct, irregular values in about [-2, 2] so a swapped texel, channel or
// slice shows up.
Texture make_texture(int w, int h, int d, int l, std::vector<std::string> channels) {
  Texture tex(w, h, d, l, std::move(channels));
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(2.0 * std::sin(0.7 * i + 0.3));
  // One value of every metadata type, so that the round trip covers each.
  set_meta(tex.metadata, "product", "transmittance");
  set_meta(tex.metadata, "mu_min", -0.20000000000000001);
  set_meta(tex.metadata, "steps", 40);
  set_meta(tex.metadata, "size", glm::ivec2(256, -64));
  set_meta(tex.metadata, "box", glm::ivec3(5, 4, 3));
  set_meta(tex.metadata, "uv", glm::dvec2(0.1, 1e-300));
  set_meta(tex.metadata, "irradiance", glm::dvec3(1.0 / 3.0, 2.5, 7e10));
  return tex;
}

struct OiioPart {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // file channel order
  float at(int x, int y, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    EXPECT_GE(c, 0) << channel;
    return pixels[(size_t(y) * spec.width + x) * spec.nchannels + c];
  }
};

// Every part of an EXR, read with OpenImageIO only.
std::vector<OiioPart> read_with_oiio(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  std::vector<OiioPart> parts;
  if (!in) return parts;
  for (int s = 0; in->seek_subimage(s, 0); ++s) {
    OiioPart part{in->spec(), {}};
    part.pixels.resize(size_t(part.spec.width) * part.spec.height * part.spec.nchannels);
    EXPECT_TRUE(
        in->read_image(s, 0, 0, part.spec.nchannels, OIIO::TypeDesc::FLOAT, part.pixels.data()));
    parts.push_back(std::move(part));
  }
  return parts;
}

void expect_textures_equal(const Texture& a, const Texture& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.layers, b.layers);
  EXPECT_EQ(a.channels, b.channels);
  EXPECT_EQ(a.metadata, b.metadata);
  ASSERT_EQ(a.data.size(), b.data.size());
  for (size_t i = 0; i < a.data.size(); ++i) ASSERT_EQ(a.data[i], b.data[i]) << "float " << i;
}

TEST(Exr, Float2DPixelsChannelsAndAttributesReadByOiio) {
  const std::string path = tmp_path("float2d", "t.exr");
  const Texture tex = make_texture(5, 3, 1, 1, {"R", "G", "B", "A", "extra"});
  write_exr(path, tex, ExrPrecision::float32);

  const auto parts = read_with_oiio(path);
  ASSERT_EQ(parts.size(), 1u);
  const OIIO::ImageSpec& spec = parts[0].spec;
  EXPECT_EQ(spec.width, 5);
  EXPECT_EQ(spec.height, 3);
  EXPECT_EQ(spec.nchannels, 5);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 5; ++c)
        EXPECT_EQ(parts[0].at(x, y, tex.channels[c]), tex.at(x, y, 0, 0, c));
  EXPECT_EQ(spec.get_string_attribute("skybake:product"), "transmittance");
  double mu_min = 0.0;  // a double attribute, not text
  EXPECT_TRUE(spec.getattribute("skybake:mu_min", OIIO::TypeDesc::DOUBLE, &mu_min));
  EXPECT_EQ(mu_min, -0.20000000000000001);
  EXPECT_EQ(spec.get_string_attribute("skybake:shape"), "5x3x1x1");
  EXPECT_EQ(spec.get_string_attribute("skybake:layout"), "image");
  EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
  EXPECT_EQ(spec.get_string_attribute("DateTime"), "");  // no time stamp
}

// Largest spacing between neighbouring halves around |v|: 2^(e - 10) for
// normal halves, 2^-24 for subnormals.
double half_ulp(double v) {
  const double a = std::fabs(v);
  if (a < std::ldexp(1.0, -14)) return std::ldexp(1.0, -24);
  return std::ldexp(1.0, int(std::floor(std::log2(a))) - 10);
}

TEST(Exr, HalfIsWithinHalfAnUlp) {
  const std::string path = tmp_path("half", "t.exr");
  Texture tex(64, 2, 1, 1, {"Y"});
  for (size_t i = 0; i < tex.data.size(); ++i)  // magnitudes 1e-6 .. 3e4, both signs
    tex.data[i] = float((i % 2 ? -1.0 : 1.0) * std::pow(10.0, -6.0 + 10.5 * i / 128.0) * 1.0137);
  write_exr(path, tex, ExrPrecision::half);

  const auto parts = read_with_oiio(path);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].spec.format, OIIO::TypeDesc::HALF);
  for (int x = 0; x < 64; ++x)
    for (int y = 0; y < 2; ++y) {
      const double v = tex.at(x, y, 0, 0, 0), got = parts[0].at(x, y, "Y");
      EXPECT_LE(std::fabs(got - v), 0.5 * half_ulp(v)) << v;
    }
}

TEST(Exr, ArrayIsOnePartPerLayer) {
  const std::string path = tmp_path("array", "t.exr");
  const Texture tex = make_texture(4, 2, 1, 3, {"R", "G", "B"});
  write_exr(path, tex, ExrPrecision::float32);

  const auto parts = read_with_oiio(path);
  ASSERT_EQ(parts.size(), 3u);
  for (int l = 0; l < 3; ++l) {
    const OIIO::ImageSpec& spec = parts[l].spec;
    EXPECT_EQ(spec.get_string_attribute("oiio:subimagename"), "layer" + std::to_string(l));
    EXPECT_EQ(spec.get_string_attribute("skybake:shape"), "4x2x1x3");
    EXPECT_EQ(spec.get_string_attribute("skybake:layout"), "layers");
    ASSERT_EQ(spec.width, 4);
    ASSERT_EQ(spec.height, 2);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(parts[l].at(x, y, "layer" + std::to_string(l) + "." + tex.channels[c]),
                    tex.at(x, y, 0, l, c));
  }
}

// OpenEXR's layer naming: every channel of a multi-part file is prefixed
// with its part's name, so no name repeats across the file (Blender refuses
// a file whose parts repeat plain R, G, B: docs/formats.md "Which tools read
// which file"); a single-part file keeps the plain names.
TEST(Exr, MultipartChannelNamesArePrefixedWithThePartAndUniqueInTheFile) {
  const Texture array = make_texture(4, 2, 1, 3, {"R", "G", "B"});
  const Texture volume = make_texture(3, 2, 4, 1, {"density"});
  const std::string a = tmp_path("naming", "array.exr"), v = tmp_path("naming", "slices.exr");
  write_exr(a, array, ExrPrecision::half);
  write_exr(v, volume, ExrPrecision::float32, ExrVolumeLayout::multipart);
  for (const auto& [path, prefix] : {std::pair{a, std::string("layer")}, std::pair{v, std::string("slice")}}) {
    SCOPED_TRACE(path);
    std::set<std::string> seen;
    const auto parts = read_with_oiio(path);
    for (size_t p = 0; p < parts.size(); ++p) {
      const std::string part = prefix + std::to_string(p);
      EXPECT_EQ(parts[p].spec.get_string_attribute("oiio:subimagename"), part);
      for (const std::string& name : parts[p].spec.channelnames) {
        EXPECT_EQ(name.rfind(part + ".", 0), 0u) << name;
        EXPECT_TRUE(seen.insert(name).second) << name << " repeats";
      }
    }
    EXPECT_EQ(seen.size(), path == a ? 9u : 4u);
  }
  const std::string single = tmp_path("naming", "image.exr");
  write_exr(single, make_texture(4, 2, 1, 1, {"R", "G"}), ExrPrecision::float32);
  std::vector<std::string> names = read_with_oiio(single).at(0).spec.channelnames;
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"G", "R"}));
}

// A foreign multi-part file with plain channel names in every part (as other
// writers make them) reads as a 2D array too.
TEST(Exr, ReadExrAcceptsAForeignMultipartFileWithPlainNames) {
  const std::string path = tmp_path("foreign_parts", "t.exr");
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(2, 1, 2, OIIO::TypeDesc::FLOAT),
                              OIIO::ImageSpec(2, 1, 2, OIIO::TypeDesc::FLOAT)};
  for (int i = 0; i < 2; ++i) {
    specs[i].channelnames = {"R", "G"};
    specs[i].attribute("oiio:subimagename", "part" + std::to_string(i));
  }
  ASSERT_TRUE(out->open(path, 2, specs));
  const float layer0[4] = {1, 2, 3, 4}, layer1[4] = {5, 6, 7, 8};
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, layer0));
  ASSERT_TRUE(out->open(path, specs[1], OIIO::ImageOutput::AppendSubimage));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, layer1));
  ASSERT_TRUE(out->close());
  const Texture tex = read_exr(path);
  EXPECT_EQ(tex.shape_string(), "2x1[2]");
  EXPECT_EQ(tex.channels, (std::vector<std::string>{"R", "G"}));
  EXPECT_EQ(tex.at(1, 0, 0, 1, 1), 8.0f);
}

TEST(Exr, VolumeAtlasPlacesSlicesInAnExactGrid) {
  const std::string path = tmp_path("atlas", "t.exr");
  const Texture tex = make_texture(3, 2, 6, 1, {"R", "G"});  // 6 slices: 3 columns, 2 rows
  write_exr(path, tex, ExrPrecision::float32, ExrVolumeLayout::atlas);

  const auto parts = read_with_oiio(path);
  ASSERT_EQ(parts.size(), 1u);
  const OIIO::ImageSpec& spec = parts[0].spec;
  ASSERT_EQ(spec.width, 9);
  ASSERT_EQ(spec.height, 4);
  EXPECT_EQ(spec.get_string_attribute("skybake:layout"), "atlas");
  EXPECT_EQ(spec.get_int_attribute("skybake:atlas_columns"), 3);
  EXPECT_EQ(spec.get_int_attribute("skybake:atlas_rows"), 2);
  EXPECT_EQ(spec.get_int_attribute("skybake:slice_width"), 3);
  EXPECT_EQ(spec.get_int_attribute("skybake:slice_height"), 2);
  EXPECT_EQ(spec.get_int_attribute("skybake:slice_count"), 6);
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x)
        for (int c = 0; c < 2; ++c)
          EXPECT_EQ(parts[0].at(x + 3 * (z % 3), y + 2 * (z / 3), tex.channels[c]),
                    tex.at(x, y, z, 0, c));
}

TEST(Exr, VolumeMultipartIsOnePartPerSlice) {
  const std::string path = tmp_path("slices", "t.exr");
  const Texture tex = make_texture(3, 2, 4, 1, {"density"});
  write_exr(path, tex, ExrPrecision::float32, ExrVolumeLayout::multipart);

  const auto parts = read_with_oiio(path);
  ASSERT_EQ(parts.size(), 4u);
  for (int z = 0; z < 4; ++z) {
    EXPECT_EQ(parts[z].spec.get_string_attribute("oiio:subimagename"), "slice" + std::to_string(z));
    EXPECT_EQ(parts[z].spec.get_string_attribute("skybake:layout"), "slices");
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x)
        EXPECT_EQ(parts[z].at(x, y, "slice" + std::to_string(z) + ".density"), tex.at(x, y, z, 0, 0));
  }
}

TEST(Exr, ReadExrRestoresEveryShapeChannelOrderAndMetadata) {
  // Channel names out of alphabetical order: EXR sorts them in the file.
  const std::vector<std::string> channels = {"zeta", "A", "R", "mid"};
  const Texture shapes[] = {make_texture(5, 3, 1, 1, channels), make_texture(4, 2, 1, 3, channels),
                            make_texture(3, 2, 5, 1, channels)};
  int n = 0;
  for (const Texture& tex : shapes)
    for (ExrVolumeLayout layout : {ExrVolumeLayout::atlas, ExrVolumeLayout::multipart}) {
      const std::string path = tmp_path("read_exr", std::to_string(n++) + ".exr");
      write_exr(path, tex, ExrPrecision::float32, layout);
      SCOPED_TRACE(path);
      expect_textures_equal(read_exr(path), tex);
    }
}

TEST(Exr, ReadExrAcceptsAForeignSinglePartFile) {
  const std::string path = tmp_path("foreign", "t.exr");
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
  const float pixels[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels) &&
              out->close());
  const Texture tex = read_exr(path);
  EXPECT_EQ(tex.shape_string(), "2x2");
  EXPECT_EQ(tex.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(tex.at(1, 1, 0, 0, 2), 12.0f);
  EXPECT_TRUE(tex.metadata.empty());
}

TEST(Exr, SameTextureGivesIdenticalBytes) {
  const Texture volume = make_texture(6, 4, 3, 1, {"R", "G", "B", "A"});
  const Texture array = make_texture(6, 4, 1, 2, {"R", "G", "B", "A"});
  int n = 0;
  for (const Texture* tex : {&volume, &array})
    for (ExrPrecision precision : {ExrPrecision::half, ExrPrecision::float32}) {
      const std::string a = tmp_path("determinism", std::to_string(n) + "a.exr");
      const std::string b = tmp_path("determinism", std::to_string(n++) + "b.exr");
      write_exr(a, *tex, precision, ExrVolumeLayout::multipart);
      write_exr(b, *tex, precision, ExrVolumeLayout::multipart);
      const std::string bytes = skybake::test::read_file(a);
      EXPECT_GT(bytes.size(), 0u);
      EXPECT_TRUE(bytes == skybake::test::read_file(b)) << a;
    }
}

TEST(Exr, NonFiniteValuesAreRefusedBeforeAFileExists) {
  for (float bad : {std::nanf(""), INFINITY}) {
    const std::string path = tmp_path("nonfinite", "t.exr");
    Texture tex = make_texture(4, 4, 1, 1, {"R"});
    tex.at(2, 1, 0, 0, 0) = bad;
    EXPECT_THROW(write_exr(path, tex, ExrPrecision::float32), IoError);
    EXPECT_FALSE(fs::exists(path));
  }
}

TEST(Exr, HalfOverflowIsRefusedButFloatKeepsIt) {
  const std::string path = tmp_path("overflow", "t.exr");
  Texture tex = make_texture(2, 2, 1, 1, {"R"});
  tex.data[3] = 70000.0f;  // rounds to Inf in half
  try {
    write_exr(path, tex, ExrPrecision::half);
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": expected values below", 0), 0u) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  write_exr(path, tex, ExrPrecision::float32);
  EXPECT_EQ(read_exr(path).data[3], 70000.0f);
}

TEST(Exr, ReservedMetadataKeysAreRefused) {
  const std::string path = tmp_path("reserved", "t.exr");
  Texture tex = make_texture(2, 2, 1, 1, {"R"});
  set_meta(tex.metadata, "shape", "mine");
  EXPECT_THROW(write_exr(path, tex, ExrPrecision::float32), Error);
  EXPECT_FALSE(fs::exists(path));
}

TEST(Exr, EveryCompressionIsLosslessAndNamedInTheHeader) {
  const Texture tex = make_texture(37, 19, 5, 1, {"R", "G", "B", "A"});
  for (const char* name : {"none", "zip", "zips", "piz"}) {
    const std::string path = tmp_path("compression", std::string(name) + ".exr");
    write_exr(path, tex, ExrPrecision::float32, ExrVolumeLayout::atlas,
              exr_compression_from_name(name));
    const auto parts = read_with_oiio(path);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_EQ(parts[0].spec.get_string_attribute("compression"), name);
    expect_textures_equal(read_exr(path), tex);
  }
  EXPECT_THROW(exr_compression_from_name("rle"), Error);
}

TEST(Exr, BytesDoNotDependOnTheThreadCount) {
  const Texture tex = make_texture(64, 80, 1, 3, {"R", "G", "B"});
  for (ExrCompression c : {ExrCompression::zip, ExrCompression::zips, ExrCompression::piz}) {
    std::string bytes[2];
    for (int threads : {1, 2}) {
      const tbb::global_control cap(tbb::global_control::max_allowed_parallelism, threads);
      const std::string path =
          tmp_path("threads", fmt::format("{}_{}.exr", int(c), threads));
      write_exr(path, tex, ExrPrecision::half, ExrVolumeLayout::atlas, c);
      bytes[threads - 1] = skybake::test::read_file(path);
    }
    EXPECT_GT(bytes[0].size(), 0u);
    EXPECT_TRUE(bytes[0] == bytes[1]) << int(c);
  }
}

}  // namespace
}  // namespace skybake

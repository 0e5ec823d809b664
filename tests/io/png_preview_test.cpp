// Tests for io/png_preview: previews are read back with OpenImageIO and
// checked against the documented layout, the sRGB transfer function
// (IEC 61966-2-1, recomputed here), monotonic tone mapping, exact 2x2 tiling
// and deterministic bytes without time stamps.
#include "io/png_preview.hpp"
#include "io/preview_font.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;

std::string tmp_path(const std::string& name, const std::string& file) {
  return skybake::test::scratch_file("io_png_preview", name, file);
}

struct Rgb8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> px;
  int at(int x, int y, int c) const { return px[(size_t(y) * width + x) * channels + c]; }
};

Rgb8 read_png(const std::string& path) {
  Rgb8 img;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return img;
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  img.width = in->spec().width;
  img.height = in->spec().height;
  img.channels = in->spec().nchannels;
  img.px.resize(size_t(img.width) * img.height * img.channels);
  EXPECT_TRUE(in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::UINT8, img.px.data()));
  return img;
}

int srgb8(double linear) {
  const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
  return int(std::lround(255.0 * s));
}

Texture constant(int w, int h, int d, int l, int channels, float value) {
  std::vector<std::string> names = {"R", "G", "B", "A", "E"};
  names.resize(channels);
  Texture tex(w, h, d, l, names);
  std::fill(tex.data.begin(), tex.data.end(), value);
  return tex;
}

TEST(PngPreview, DimensionsFollowTheDocumentedLayout) {
  struct Case {
    Texture tex;
    PreviewOptions opt;
    int width, height;
  };
  PreviewOptions all_slices;
  all_slices.max_slices = 0;
  PreviewOptions tiled_split;
  tiled_split.tile_2x2 = true;
  tiled_split.split_channels = true;
  const Case cases[] = {
      {constant(7, 5, 1, 1, 3, 0.2f), {}, 7, 5},
      {constant(4, 3, 1, 3, 4, 0.2f), {}, 12, 3},               // layers side by side
      {constant(4, 3, 20, 1, 1, 0.2f), {}, 32, 3},              // 8 of 20 slices in a row
      {constant(4, 3, 20, 1, 1, 0.2f), all_slices, 32, 9},      // 20 slices, 8 per row
      {constant(4, 3, 1, 1, 4, 0.2f), tiled_split, 32, 6},      // 4 channels, each 2x2
      {constant(4, 3, 2, 1, 2, 0.2f), tiled_split, 2 * 16, 6},  // 2 slices of 2 channels
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string path = tmp_path("dimensions", std::to_string(n++) + ".png");
    write_png_preview(path, c.tex, c.opt);
    const Rgb8 img = read_png(path);
    EXPECT_EQ(img.width, c.width) << path;
    EXPECT_EQ(img.height, c.height) << path;
    EXPECT_EQ(img.channels, 3) << path;
  }
}

// min_side enlarges each short axis by whole pixels per texel (a 1 x 8
// profile at 4 becomes 4 x 8; 2 x 3 at 5 becomes blocks of 3 x 2, 6 x 6),
// and height_up draws texture row 0 at the bottom.
TEST(PngPreview, SmallTexturesAreEnlargedAndHeightsRiseUpward) {
  Texture profile(1, 8, 1, 1, {"R"});
  for (int y = 0; y < 8; ++y) profile.at(0, y, 0, 0, 0) = float(y) / 7.0f;  // row 0 lowest
  PreviewOptions opt;
  opt.min_side = 4;
  const std::string path = tmp_path("enlarged", "profile.png");
  write_png_preview(path, profile, opt);
  Rgb8 img = read_png(path);
  ASSERT_EQ(img.width, 4);
  ASSERT_EQ(img.height, 8);
  auto grey = [](const Rgb8& im, int x, int y) { return im.at(x, y, 0); };
  for (int x = 0; x < 4; ++x) EXPECT_EQ(grey(img, x, 0), grey(img, 0, 0));  // one texel, 4 px
  EXPECT_LT(grey(img, 0, 0), grey(img, 0, 7));  // row 0 (0.0) on top, as stored
  opt.height_up = true;
  write_png_preview(path, profile, opt);
  img = read_png(path);
  EXPECT_GT(grey(img, 0, 0), grey(img, 0, 7));  // row 7 (1.0) on top: heights rise
  EXPECT_EQ(grey(img, 0, 0), 255);
  EXPECT_EQ(grey(img, 0, 7), 0);

  Texture small(2, 3, 1, 1, {"R"});
  small.at(1, 2, 0, 0, 0) = 1.0f;
  opt = PreviewOptions{};
  opt.min_side = 5;  // ceil(5 / 2) = 3 across, ceil(5 / 3) = 2 down
  write_png_preview(path, small, opt);
  img = read_png(path);
  ASSERT_EQ(img.width, 6);
  ASSERT_EQ(img.height, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x)
      EXPECT_EQ(grey(img, x, y), x >= 3 && y >= 4 ? 255 : 0) << x << " " << y;
  // Textures already as large keep one pixel per texel.
  EXPECT_EQ(preview_layout(constant(7, 5, 1, 1, 3, 0.2f), opt).width, 7);
}

// Labels (label_channels): a band above each channel names it and says what
// its second line means: "0 EVERYWHERE" for an all-zero channel, whose
// panel stays black, and "<min>-<max> STRETCHED" for a narrow [0, 1]
// channel that stretch_narrow maps to the full range.
TEST(PngPreview, ChannelLabelsSayConstantAndStretchedChannels) {
  EXPECT_EQ(preview_range_label(0.0, 0.0, false), "0 EVERYWHERE");
  EXPECT_EQ(preview_range_label(0.5, 0.5, false), "0.5 EVERYWHERE");
  EXPECT_EQ(preview_range_label(0.7, 0.94, true), "0.70-0.94 STRETCHED");
  EXPECT_EQ(preview_range_label(0.0, 1.0, false), "");

  Texture tex(128, 16, 1, 1, {"R", "G"});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 128; ++x) tex.at(x, y, 0, 0, 1) = 0.7f + 0.24f * float(x) / 127.0f;
  PreviewOptions opt;
  opt.split_channels = opt.label_channels = opt.stretch_narrow = true;
  const PreviewLayout layout = preview_layout(tex, opt);
  ASSERT_GT(layout.label_height, 0);
  const std::string path = tmp_path("labels", "t.png");
  write_png_preview(path, tex, opt);
  const Rgb8 img = read_png(path);
  ASSERT_EQ(img.width, 256);
  ASSERT_EQ(img.height, 16 + layout.label_height);
  const int band = layout.label_height;
  for (int y = band; y < img.height; ++y) {
    for (int x = 0; x < 128; ++x) ASSERT_EQ(img.at(x, y, 0), 0) << "R is 0 everywhere";
    EXPECT_EQ(img.at(128, y, 0), 0);    // G's minimum maps to black
    EXPECT_EQ(img.at(255, y, 0), 255);  // and its maximum to white
  }
  // The band holds exactly the two lines of each channel, drawn by the font.
  std::vector<uint8_t> expected(size_t(256) * band * 3, 0);
  draw_preview_text(expected, 256, band, 1, 1, "R", 2, 255);
  draw_preview_text(expected, 256, band, 1, 1 + band / 2, "0 EVERYWHERE", 2, 255);
  draw_preview_text(expected, 256, band, 129, 1, "G", 2, 255);
  draw_preview_text(expected, 256, band, 129, 1 + band / 2, "0.70-0.94 STRETCHED", 1, 255);
  for (int y = 0; y < band; ++y)
    for (int x = 0; x < 256; ++x)
      ASSERT_EQ(img.at(x, y, 0), expected[(size_t(y) * 256 + x) * 3]) << x << " " << y;
}

// Panel labels: one line above each panel, by the panel's layer (or slice).
TEST(PngPreview, PanelLabelsStandAboveTheirPanels) {
  Texture tex(60, 8, 1, 3, {"R", "G", "B"});
  PreviewOptions opt;
  opt.panel_labels = {"SUN 60", "SUN 10", "SUN -3"};
  opt.max_columns = 2;
  const PreviewLayout layout = preview_layout(tex, opt);
  ASSERT_GT(layout.label_height, 0);
  const std::string path = tmp_path("panel_labels", "t.png");
  write_png_preview(path, tex, opt);
  const Rgb8 img = read_png(path);
  ASSERT_EQ(img.width, 120);
  ASSERT_EQ(img.height, 2 * (8 + layout.label_height));
  std::vector<uint8_t> expected(size_t(120) * img.height * 3, 0);
  draw_preview_text(expected, 120, img.height, 1, 1, "SUN 60", 2, 255);
  draw_preview_text(expected, 120, img.height, 61, 1, "SUN 10", 2, 255);
  draw_preview_text(expected, 120, img.height, 1, 1 + 8 + layout.label_height, "SUN -3", 2, 255);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < 120; ++x)
      ASSERT_EQ(img.at(x, y, 0), expected[(size_t(y) * 120 + x) * 3]) << x << " " << y;
}

TEST(PngPreview, ConstantHalfWithoutTonemapIsSrgbHalf) {
  const std::string path = tmp_path("constant", "t.png");
  PreviewOptions opt;
  opt.tonemap = Tonemap::none;
  write_png_preview(path, constant(3, 2, 1, 1, 3, 0.5f), opt);
  const Rgb8 img = read_png(path);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y, c), 188, 1);
}

TEST(PngPreview, GradientsMapMonotonically) {
  for (Tonemap tonemap : {Tonemap::none, Tonemap::reinhard, Tonemap::aces})
    for (double top : {1.0, 100.0}) {  // [0, 1] data, then HDR data (auto exposure)
      const std::string path = tmp_path("gradient", "t.png");
      Texture tex(64, 1, 1, 1, {"L"});
      for (int x = 0; x < 64; ++x) tex.data[x] = float(top * x / 63.0);
      PreviewOptions opt;
      opt.tonemap = tonemap;
      write_png_preview(path, tex, opt);
      const Rgb8 img = read_png(path);
      ASSERT_EQ(img.width, 64);
      EXPECT_EQ(img.at(0, 0, 0), 0);
      for (int x = 1; x < 64; ++x) {
        EXPECT_GE(img.at(x, 0, 0), img.at(x - 1, 0, 0)) << x;
        EXPECT_EQ(img.at(x, 0, 1), img.at(x, 0, 0));  // one channel shows as grey
      }
      EXPECT_GT(img.at(63, 0, 0), 150) << int(tonemap) << " " << top;
    }
}

TEST(PngPreview, UnitDataIsShownAsIsAndHdrIsScaledToItsPercentile) {
  Texture unit(100, 1, 1, 1, {"L"});
  Texture hdr(100, 1, 1, 1, {"L"});
  for (int x = 0; x < 100; ++x) {
    unit.data[x] = float(x) / 99.0f;
    hdr.data[x] = 1000.0f * float(x) / 99.0f;
  }
  const std::string a = tmp_path("auto", "unit.png"), b = tmp_path("auto", "hdr.png");
  write_png_preview(a, unit, {});
  write_png_preview(b, hdr, {});
  const Rgb8 ia = read_png(a), ib = read_png(b);
  for (int x = 0; x < 100; x += 9) EXPECT_NEAR(ia.at(x, 0, 0), srgb8(x / 99.0), 1) << x;
  // The 99th percentile of 100 evenly spaced values is the 99th of them
  // (index 98): it and everything below stay below white, the top clips.
  EXPECT_EQ(ib.at(98, 0, 0), 255);
  EXPECT_LT(ib.at(97, 0, 0), 255);
  EXPECT_NEAR(ib.at(49, 0, 0), srgb8(49.0 / 98.0), 1);
}

TEST(PngPreview, SignedDataCentresZeroOnMidGrey) {
  const std::string path = tmp_path("signed", "t.png");
  Texture tex(3, 1, 1, 1, {"curl"});
  tex.data = {-1.0f, 0.0f, 1.0f};
  write_png_preview(path, tex, {});
  const Rgb8 img = read_png(path);
  EXPECT_EQ(img.at(0, 0, 0), 0);
  EXPECT_NEAR(img.at(1, 0, 0), srgb8(0.5), 1);
  EXPECT_EQ(img.at(2, 0, 0), 255);
}

TEST(PngPreview, ChannelsMapToColourAndAlphaIsNotShown) {
  Texture two(2, 2, 1, 1, {"R", "G"});
  Texture rgba(2, 2, 1, 1, {"R", "G", "B", "A"});
  for (int t = 0; t < 4; ++t) {
    two.data[t * 2] = 0.25f, two.data[t * 2 + 1] = 0.75f;
    rgba.data[t * 4] = 0.1f, rgba.data[t * 4 + 1] = 0.2f, rgba.data[t * 4 + 2] = 0.3f;
    rgba.data[t * 4 + 3] = t % 2 ? 1.0f : 0.0f;
  }
  const std::string a = tmp_path("channels", "two.png"), b = tmp_path("channels", "rgba.png");
  write_png_preview(a, two, {});
  write_png_preview(b, rgba, {});
  const Rgb8 ia = read_png(a), ib = read_png(b);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      EXPECT_NEAR(ia.at(x, y, 0), srgb8(0.25), 1);
      EXPECT_NEAR(ia.at(x, y, 1), srgb8(0.75), 1);
      EXPECT_EQ(ia.at(x, y, 2), 0);
      EXPECT_NEAR(ib.at(x, y, 0), srgb8(0.1), 1);
      EXPECT_NEAR(ib.at(x, y, 1), srgb8(0.2), 1);
      EXPECT_NEAR(ib.at(x, y, 2), srgb8(0.3), 1);
    }
}

TEST(PngPreview, SplitChannelsShowsEachChannelAsGrey) {
  const std::string path = tmp_path("split", "t.png");
  Texture tex(2, 1, 1, 1, {"R", "G", "B", "A"});
  const float values[4] = {0.1f, 0.4f, 0.7f, 1.0f};
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 4; ++c) tex.at(x, 0, 0, 0, c) = values[c];
  PreviewOptions opt;
  opt.split_channels = true;
  write_png_preview(path, tex, opt);
  const Rgb8 img = read_png(path);
  ASSERT_EQ(img.width, 8);
  for (int c = 0; c < 4; ++c)
    for (int x = 0; x < 2; ++x)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(img.at(2 * c + x, 0, k), srgb8(values[c]), 1);
}

TEST(PngPreview, VolumeSlicesAreEvenlyPickedInOrder) {
  EXPECT_EQ(preview_slices(16, 8), (std::vector<int>{0, 2, 4, 6, 8, 10, 12, 14}));
  EXPECT_EQ(preview_slices(5, 8), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(preview_slices(3, 0), (std::vector<int>{0, 1, 2}));

  const std::string path = tmp_path("slices", "t.png");
  Texture tex(2, 2, 16, 1, {"L"});
  for (int z = 0; z < 16; ++z)
    for (int i = 0; i < 4; ++i) tex.data[z * 4 + i] = float(z) / 15.0f;
  write_png_preview(path, tex, {});
  const Rgb8 img = read_png(path);
  ASSERT_EQ(img.width, 16);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(img.at(2 * k + 1, 1, 0), srgb8(2 * k / 15.0), 1) << k;
}

TEST(PngPreview, Tile2x2RepeatsThePanelExactly) {
  Texture tex(5, 3, 1, 1, {"R", "G", "B"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(0.5 + 0.5 * std::sin(1.3 * i));
  PreviewOptions tiled;
  tiled.tile_2x2 = true;
  const std::string a = tmp_path("tile", "plain.png"), b = tmp_path("tile", "tiled.png");
  write_png_preview(a, tex, {});
  write_png_preview(b, tex, tiled);
  const Rgb8 plain = read_png(a), img = read_png(b);
  ASSERT_EQ(img.width, 10);
  ASSERT_EQ(img.height, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 10; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), plain.at(x % 5, y % 3, c));
}

// PNG chunks in file order as (type, data) (PNG spec sec. 5.3: length, type,
// data, CRC).
std::vector<std::pair<std::string, std::string>> png_chunks(const std::string& bytes) {
  std::vector<std::pair<std::string, std::string>> chunks;
  for (size_t p = 8; p + 8 <= bytes.size();) {
    const auto b = [&](size_t i) { return uint32_t(uint8_t(bytes[p + i])); };
    const uint32_t length = b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
    chunks.emplace_back(bytes.substr(p + 4, 4), bytes.substr(p + 8, length));
    p += 12 + length;
  }
  return chunks;
}

TEST(PngPreview, BytesAreDeterministicWithoutTimeStamps) {
  Texture tex(6, 4, 3, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(5.0 + 4.0 * std::sin(0.9 * i));
  const std::string a = tmp_path("determinism", "a.png"), b = tmp_path("determinism", "b.png");
  write_png_preview(a, tex, {});
  write_png_preview(b, tex, {});
  const std::string bytes = skybake::test::read_file(a);
  EXPECT_TRUE(bytes == skybake::test::read_file(b));
  const auto chunks = png_chunks(bytes);
  ASSERT_FALSE(chunks.empty());
  EXPECT_EQ(chunks.front().first, "IHDR");
  EXPECT_EQ(chunks.back().first, "IEND");
  for (const auto& [type, data] : chunks) {
    EXPECT_NE(type, "tIME");
    if (type != "tEXt" && type != "zTXt" && type != "iTXt") continue;
    const std::string keyword = data.substr(0, data.find('\0'));  // sec. 11.3.4
    for (const char* stamp : {"Time", "Date", "Software", "Host"})
      EXPECT_EQ(keyword.find(stamp), std::string::npos) << keyword;
  }
}

TEST(PngPreview, NonFiniteValuesAreRefusedBeforeAFileExists) {
  const std::string path = tmp_path("nonfinite", "t.png");
  Texture tex = constant(3, 3, 1, 1, 1, 0.5f);
  tex.data[4] = std::nanf("");
  EXPECT_THROW(write_png_preview(path, tex, {}), IoError);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace skybake

// The EXR header as OpenEXR's own typed API sees it (docs/formats.md "EXR"):
// every metadata value is an attribute of its type with its value, no date
// is written, and a volume's atlas has exactly depth cells, the factor pair
// closest to a square, recorded in int attributes. Pixels are checked with
// OpenImageIO, which shares no code with read_exr, and round trips are exact.
#include <cmath>
#include <set>
#include <string>

#include <ImfDoubleAttribute.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "io/exr.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

std::string tmp_path(const std::string& name) {
  return test::scratch_file("io_exr_attributes", name, "t.exr");
}

Texture volume(int w, int h, int d) {
  Texture tex(w, h, d, 1, {"R", "G"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(std::sin(0.37 * i + 0.2));
  return tex;
}

TEST(ExrAttributes, EveryMetadataTypeIsItsOwnAttributeType) {
  Texture tex = volume(3, 2, 1);
  set_meta(tex.metadata, "count", -12);
  set_meta(tex.metadata, "g", 0.76000000000000001);
  set_meta(tex.metadata, "name", "bruneton_4d_scattering");
  set_meta(tex.metadata, "orders", glm::ivec2(1, 4));
  set_meta(tex.metadata, "cells", glm::ivec3(8, 4, 32));
  set_meta(tex.metadata, "range", glm::dvec2(-1.0, 1.0));
  set_meta(tex.metadata, "sun", glm::dvec3(1.0 / 3.0, 1e-300, 7e10));
  const std::string path = tmp_path("types");
  write_exr(path, tex, ExrPrecision::float32);

  Imf::MultiPartInputFile in(path.c_str());
  const Imf::Header& h = in.header(0);
  const auto* count = h.findTypedAttribute<Imf::IntAttribute>("skybake:count");
  const auto* g = h.findTypedAttribute<Imf::DoubleAttribute>("skybake:g");
  const auto* name = h.findTypedAttribute<Imf::StringAttribute>("skybake:name");
  const auto* orders = h.findTypedAttribute<Imf::V2iAttribute>("skybake:orders");
  const auto* cells = h.findTypedAttribute<Imf::V3iAttribute>("skybake:cells");
  const auto* range = h.findTypedAttribute<Imf::V2dAttribute>("skybake:range");
  const auto* sun = h.findTypedAttribute<Imf::V3dAttribute>("skybake:sun");
  ASSERT_TRUE(count && g && name && orders && cells && range && sun);
  EXPECT_EQ(count->value(), -12);
  EXPECT_EQ(g->value(), 0.76000000000000001);
  EXPECT_EQ(name->value(), "bruneton_4d_scattering");
  EXPECT_EQ(orders->value(), Imath::V2i(1, 4));
  EXPECT_EQ(cells->value(), Imath::V3i(8, 4, 32));
  EXPECT_EQ(range->value(), Imath::V2d(-1.0, 1.0));
  EXPECT_EQ(sun->value(), Imath::V3d(1.0 / 3.0, 1e-300, 7e10));
  // No number hides in a string: every string attribute of ours is text.
  for (auto it = h.begin(); it != h.end(); ++it) {
    const std::string attr = it.name();
    if (attr.rfind("skybake:", 0) != 0 || std::string(it.attribute().typeName()) != "string")
      continue;
    EXPECT_TRUE(attr == "skybake:name" || attr == "skybake:shape" ||
                attr == "skybake:channels" || attr == "skybake:layout")
        << attr;
  }
  const Texture back = read_exr(path);
  EXPECT_EQ(back.metadata, tex.metadata);
}

TEST(ExrAttributes, NoDateOrTimeIsWritten) {
  Texture tex = volume(4, 4, 1);
  set_meta(tex.metadata, "product", "transmittance");
  for (const ExrVolumeLayout layout : {ExrVolumeLayout::atlas, ExrVolumeLayout::multipart}) {
    const Texture shapes[] = {tex, volume(2, 2, 6)};
    for (const Texture& t : shapes) {
      const std::string path = tmp_path("no_date");
      write_exr(path, t, ExrPrecision::half, layout);
      Imf::MultiPartInputFile in(path.c_str());
      for (int p = 0; p < in.parts(); ++p) {
        const Imf::Header& h = in.header(p);
        // OpenEXR's standard attributes for capture time (ImfStandardAttributes.h).
        EXPECT_TRUE(h.find("capDate") == h.end());
        EXPECT_TRUE(h.find("utcOffset") == h.end());
        for (auto it = h.begin(); it != h.end(); ++it) {
          std::string lower = it.name();
          for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
          EXPECT_EQ(lower.find("date"), std::string::npos) << it.name();
          EXPECT_EQ(lower.find("time"), std::string::npos) << it.name();
        }
      }
    }
  }
}

// The factor pair closest to a square: rows the largest divisor of depth not
// above sqrt(depth), a prime depth one row.
TEST(ExrAttributes, AtlasHasExactlyDepthCells) {
  const struct {
    int depth, columns, rows;
  } cases[] = {{32, 8, 4}, {128, 16, 8}, {7, 7, 1}, {1, 1, 1}, {12, 4, 3}, {36, 6, 6}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.depth);
    EXPECT_EQ(exr_atlas_columns(c.depth), c.columns);
    EXPECT_EQ(c.depth / exr_atlas_columns(c.depth), c.rows);
  }
  for (int depth = 1; depth <= 600; ++depth) {
    const int columns = exr_atlas_columns(depth), rows = depth / columns;
    ASSERT_EQ(columns * rows, depth) << depth;
    ASSERT_GE(columns, rows) << depth;
    for (int r = rows + 1; r * r <= depth; ++r) ASSERT_NE(depth % r, 0) << depth << " " << r;
  }
}

TEST(ExrAttributes, AtlasLayoutIsRecordedAndPlacesEverySlice) {
  for (const int depth : {32, 128, 7}) {
    SCOPED_TRACE(depth);
    const Texture tex = volume(3, 2, depth);
    const std::string path = tmp_path("atlas" + std::to_string(depth));
    write_exr(path, tex, ExrPrecision::float32, ExrVolumeLayout::atlas);
    Imf::MultiPartInputFile in(path.c_str());
    ASSERT_EQ(in.parts(), 1);
    const Imf::Header& h = in.header(0);
    const auto int_attr = [&](const char* key) {
      const auto* a = h.findTypedAttribute<Imf::IntAttribute>(std::string("skybake:") + key);
      EXPECT_NE(a, nullptr) << key;
      return a ? a->value() : -1;
    };
    const int columns = int_attr("atlas_columns"), rows = int_attr("atlas_rows");
    EXPECT_EQ(columns, exr_atlas_columns(depth));
    EXPECT_EQ(columns * rows, depth);
    EXPECT_EQ(int_attr("slice_count"), depth);
    EXPECT_EQ(int_attr("slice_width"), 3);
    EXPECT_EQ(int_attr("slice_height"), 2);
    const Imath::Box2i dw = h.dataWindow();
    EXPECT_EQ(dw.max.x + 1, 3 * columns);
    EXPECT_EQ(dw.max.y + 1, 2 * rows);

    auto image = OIIO::ImageInput::open(path);
    ASSERT_TRUE(image);
    const OIIO::ImageSpec spec = image->spec();
    std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(image->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    const int r = spec.channelindex("R"), g = spec.channelindex("G");
    ASSERT_TRUE(r >= 0 && g >= 0);
    for (int z = 0; z < depth; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
          const size_t px = size_t(x + 3 * (z % columns)), py = size_t(y + 2 * (z / columns));
          const float* p = &pixels[(py * spec.width + px) * spec.nchannels];
          ASSERT_EQ(p[r], tex.at(x, y, z, 0, 0)) << x << " " << y << " " << z;
          ASSERT_EQ(p[g], tex.at(x, y, z, 0, 1)) << x << " " << y << " " << z;
        }
    const Texture back = read_exr(path);
    EXPECT_EQ(back.shape_string(), tex.shape_string());
    EXPECT_TRUE(back.data == tex.data) << "round trip exact";
  }
  // Depth 1 is no volume: a plain image, read back as it was.
  const Texture flat = volume(3, 2, 1);
  const std::string path = tmp_path("atlas1");
  write_exr(path, flat, ExrPrecision::float32, ExrVolumeLayout::atlas);
  Imf::MultiPartInputFile in(path.c_str());
  EXPECT_EQ(in.header(0).findTypedAttribute<Imf::StringAttribute>("skybake:layout")->value(),
            "image");
  EXPECT_TRUE(read_exr(path).data == flat.data);
}

}  // namespace
}  // namespace skybake

#include "core/metadata.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/metadata_json.hpp"

namespace skybake {
namespace {

using ::testing::HasSubstr;

Metadata every_type() {
  Metadata m;
  set_meta(m, "i", -7);
  set_meta(m, "d", 0.1);
  set_meta(m, "whole", 2.0);
  set_meta(m, "s", "text");
  set_meta(m, "i2", glm::ivec2(1, -3));
  set_meta(m, "i3", glm::ivec3(4, 5, 6));
  set_meta(m, "d2", glm::dvec2(1.0, 1e-300));
  set_meta(m, "d3", glm::dvec3(5.8e-6, 1.35e-5, 3.31e-5));
  return m;
}

TEST(Metadata, TypedReadersReturnWhatWasSet) {
  const Metadata m = every_type();
  EXPECT_EQ(meta_int(m, "i"), -7);
  EXPECT_EQ(meta_double(m, "d"), 0.1);
  EXPECT_EQ(meta_string(m, "s"), "text");
  EXPECT_EQ(meta_int2(m, "i2"), glm::ivec2(1, -3));
  EXPECT_EQ(meta_int3(m, "i3"), glm::ivec3(4, 5, 6));
  EXPECT_EQ(meta_double2(m, "d2"), glm::dvec2(1.0, 1e-300));
  EXPECT_EQ(meta_double3(m, "d3"), glm::dvec3(5.8e-6, 1.35e-5, 3.31e-5));
  EXPECT_EQ(meta_type_name(m.at("d3")), "double3");
}

TEST(Metadata, MissingKeysAndWrongTypesAreNamedErrors) {
  const Metadata m = every_type();
  try {
    meta_double(m, "absent");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "metadata 'absent': missing");
  }
  try {
    meta_double(m, "i");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "metadata 'i': expected double, got int -7");
  }
  EXPECT_THROW(meta_int(m, "d"), Error) << "no conversion from double";
  EXPECT_THROW(meta_string(m, "i"), Error);
  EXPECT_THROW(meta_double3(m, "d2"), Error);
  EXPECT_EQ(find_meta<int>(m, "d"), nullptr);
  ASSERT_NE(find_meta<double>(m, "d"), nullptr);
}

TEST(MetadataJson, RoundTripKeepsEveryType) {
  const Metadata m = every_type();
  const nlohmann::json j = metadata_to_json(m);
  EXPECT_TRUE(j["i"].is_number_integer());
  EXPECT_TRUE(j["whole"].is_number_float());
  EXPECT_EQ(j["d3"].size(), 3u);
  // Through text, as the manifest stores it.
  const Metadata back = metadata_from_json(nlohmann::json::parse(j.dump(2)));
  EXPECT_EQ(back, m);
  EXPECT_EQ(meta_type_name(back.at("whole")), "double");
  EXPECT_EQ(meta_type_name(back.at("i2")), "int2");
}

TEST(MetadataJson, NonFiniteDoublesAreNullAndReadBackAsNaN) {
  Metadata m;
  set_meta(m, "x", std::numeric_limits<double>::infinity());
  const nlohmann::json j = metadata_to_json(m);
  EXPECT_TRUE(j["x"].is_null());
  EXPECT_TRUE(std::isnan(meta_double(metadata_from_json(j), "x")));
}

TEST(MetadataJson, OtherShapesAreRefusedWithTheKey) {
  for (const char* text : {R"({"k": [1, 2, 3, 4]})", R"({"k": [1, 2.5]})", R"({"k": {"a": 1}})",
                           R"({"k": true})", R"({"k": 4294967296})", R"({"k": ["a", "b"]})"}) {
    SCOPED_TRACE(text);
    try {
      metadata_from_json(nlohmann::json::parse(text));
      FAIL();
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("metadata/k: expected"));
    }
  }
}

// A person reads the shortest text that parses back to the same double:
// 0.09 as "0.09", not its 17-digit expansion "0.089999999999999997".
TEST(Metadata, TextIsTheShortestThatReadsBackExactly) {
  EXPECT_EQ(meta_text(MetaValue(0.09)), "0.09");
  EXPECT_EQ(meta_text(MetaValue(2.0)), "2");
  EXPECT_EQ(meta_text(MetaValue(-0.2)), "-0.2");
  EXPECT_EQ(meta_text(MetaValue(glm::dvec3(5.8e-6, 1.35e-5, 3.31e-5))),
            "[5.8e-06, 1.35e-05, 3.31e-05]");
  EXPECT_EQ(meta_text(MetaValue(glm::dvec2(1.0, 1e-300))), "[1, 1e-300]");
  EXPECT_EQ(meta_text(MetaValue(7)), "7");
  // Every double reads back exactly, and no shorter text would: dropping
  // the last significant digit changes the value.
  uint64_t bits = 0x3FB70A3D70A3D70Aull;  // near 0.09
  for (int i = 0; i < 2000; ++i) {
    bits = bits * 6364136223846793005ull + 1442695040888963407ull;
    double v;
    const uint64_t finite = (bits & 0x800FFFFFFFFFFFFFull) | (uint64_t((bits >> 52) % 2046 + 1) << 52);
    std::memcpy(&v, &finite, sizeof v);
    const std::string text = meta_text(MetaValue(v));
    ASSERT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
    const size_t e = text.find('e');
    std::string mantissa = text.substr(0, e);
    const std::string exponent = e == std::string::npos ? "" : text.substr(e);
    if (mantissa.find('.') == std::string::npos || mantissa.size() < 3) continue;
    mantissa.pop_back();
    if (mantissa.back() == '.') mantissa.pop_back();
    EXPECT_NE(std::strtod((mantissa + exponent).c_str(), nullptr), v) << text;
  }
}

}  // namespace
}  // namespace skybake

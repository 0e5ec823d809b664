// Tests for the DDS format names of io/dds.hpp: each name and its
// DXGI_FORMAT code as Microsoft's "DXGI_FORMAT enumeration" documents them,
// and the refusal of an unknown name with the list and the nearest match.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/dds.hpp"

namespace skybake {
namespace {

using ::testing::HasSubstr;

TEST(DdsFormatName, RoundTripsAndDxgiCodes) {
  const std::vector<std::pair<const char*, uint32_t>> documented = {
      {"R32G32B32A32_FLOAT", 2}, {"R16G16B16A16_FLOAT", 10}, {"R11G11B10_FLOAT", 26},
      {"R8G8B8A8_UNORM", 28},    {"R8G8_UNORM", 49},         {"R16_FLOAT", 54},
      {"R8_UNORM", 61},          {"BC1_UNORM", 71},          {"BC3_UNORM", 77},
      {"BC4_UNORM", 80},         {"BC5_UNORM", 83}};
  ASSERT_EQ(dds_formats().size(), documented.size());
  for (const auto& [name, code] : documented) {
    const DdsFormat f = dds_format_from_name(name);
    EXPECT_EQ(uint32_t(f), code) << name;
    EXPECT_STREQ(dxgi_format_name(f), name);
    EXPECT_EQ(dds_format_from_name(std::string("DXGI_FORMAT_") + name), f);
  }
}

TEST(DdsFormatName, UnknownNameListsValidOnesAndSuggests) {
  EXPECT_THAT([] { dds_format_from_name("R16G16B16A16_FLOT", "presets/x.json: /dds/format"); },
              ::testing::ThrowsMessage<IoError>(::testing::AllOf(
                  HasSubstr("presets/x.json: /dds/format: expected one of R32G32B32A32_FLOAT, "
                            "R16G16B16A16_FLOAT, R11G11B10_FLOAT, R8G8B8A8_UNORM, R8G8_UNORM, "
                            "R16_FLOAT, R8_UNORM, BC1_UNORM, BC3_UNORM, BC4_UNORM, BC5_UNORM, "
                            "got \"R16G16B16A16_FLOT\""),
                  HasSubstr("did you mean \"R16G16B16A16_FLOAT\"?"))));
  EXPECT_EQ(dds_format_from_name("R8_UNORM"), DdsFormat::R8_UNORM);
  EXPECT_THAT([] { dds_format_from_name("r8_unorm"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("did you mean \"R8_UNORM\"?")));
  EXPECT_THAT([] { dds_format_from_name("ASTC_4X4_UNORM_SRGB"); },
              ::testing::ThrowsMessage<IoError>(::testing::Not(HasSubstr("did you mean"))));
}

}  // namespace
}  // namespace skybake
